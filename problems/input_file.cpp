#include "problems/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"

namespace rb {

namespace {

constexpr std::size_t kLongestShownPath = 4096;  // PATH_MAX

// what a file that is not a regular file is, in words
const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

InputKind reference_cache_input(std::size_t output_times) {
  return {"cached reference", kReferenceBaseBytes + kReferenceBytesPerTime * output_times};
}

std::string size_in_words(unsigned long long bytes) {
  if (bytes < 1000) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  const char* units[] = {"kB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes) / 1000.0;
  std::size_t unit = 0;
  while (value >= 999.5 && unit + 1 < sizeof units / sizeof *units) value /= 1000.0, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %s", value, units[unit]);
  return text;
}

std::string limit_in_words(std::size_t bytes) {
  if (bytes >= kGiB && bytes % kGiB == 0) return std::to_string(bytes / kGiB) + " GiB";
  if (bytes >= kMiB && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
  if (bytes >= kKiB && bytes % kKiB == 0) return std::to_string(bytes / kKiB) + " KiB";
  return size_in_words(bytes);
}

std::string shown_path(const std::string& path) { return escaped_excerpt(path, kLongestShownPath); }

std::string read_open_input(int fd, const std::string& path, const InputKind& kind, const std::string& key) {
  const std::string quoted = "'" + shown_path(path) + "'";
  const std::string limit = "; a " + kind.name + " is at most " + limit_in_words(kind.max_bytes);
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    throw InputError("cannot read the " + kind.name + " " + quoted + " (" + std::strerror(errno) + ")", key);
  if (!S_ISREG(st.st_mode))
    throw InputError(quoted + " is " + kind_of(st.st_mode) + "; inputs are read only from regular files", key);
  if (static_cast<unsigned long long>(st.st_size) > kind.max_bytes)
    throw InputError(quoted + " is " + size_in_words(static_cast<unsigned long long>(st.st_size)) + limit, key);
  // at most max_bytes + 1: one byte past the limit tells a file that grew
  std::string text(static_cast<std::size_t>(st.st_size) + 1, '\0');
  std::size_t have = 0;
  for (;;) {
    if (have == text.size()) {
      if (have > kind.max_bytes)
        throw InputError(quoted + " grew past " + limit_in_words(kind.max_bytes) + " while it was read" + limit, key);
      text.resize(std::min(kind.max_bytes + 1, have + 64 * kKiB));
    }
    const ssize_t got = ::read(fd, text.data() + have, text.size() - have);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0)
      throw InputError("cannot read the " + kind.name + " " + quoted + " (" + std::strerror(errno) + ")", key);
    if (got == 0) break;
    have += static_cast<std::size_t>(got);
  }
  text.resize(have);
  return text;
}

std::string read_input_file(const std::string& path, const InputKind& kind, const std::string& key) {
  // O_NONBLOCK: opening a FIFO without a writer returns at once (and is
  // refused as a FIFO); O_NOCTTY: a terminal never becomes ours
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0)
    throw InputError("cannot read the " + kind.name + " '" + shown_path(path) + "' (" + std::strerror(errno) + ")",
                     key);
  try {
    std::string text = read_open_input(fd, path, kind, key);
    ::close(fd);
    return text;
  } catch (...) {
    ::close(fd);
    throw;
  }
}

}  // namespace rb

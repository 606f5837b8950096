#include "bench/lib/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>

#include "problems/input_error.hpp"

namespace rb {

namespace {

std::atomic<unsigned long> temporary_counter{0};

// ".NAME.tmp.PID.N.T" in the target's folder: unique per process and call,
// hidden, and on the same file system so that rename is atomic.
std::string temporary_name(const std::string& path) {
  const std::filesystem::path p(path);
  const auto nanoseconds = std::chrono::steady_clock::now().time_since_epoch().count();
  // appended piece by piece: "." + std::string(...) trips GCC 12's false -Wrestrict
  std::string name = ".";
  name += p.filename().string();
  name += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(temporary_counter++) + "." +
          std::to_string(nanoseconds % 1000000007);
  return (p.parent_path() / name).string();
}

bool is_other_than_regular_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

}  // namespace

OutputFile::OutputFile(std::string path, std::string option) : path_(std::move(path)), option_(std::move(option)) {
  const auto refuse = [&] { throw InputError("cannot open '" + path_ + "' for writing", option_); };
  if (path_.empty() || path_.back() == '/') refuse();
  if (is_other_than_regular_file(path_)) {
    if (std::filesystem::is_directory(path_)) refuse();
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) refuse();
    return;
  }
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    temporary_ = temporary_name(path_);
    // 0666 less the umask: the mode a plain open would give the file
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ < 0 && errno != EEXIST) break;
  }
  if (fd_ < 0) {
    temporary_.clear();
    refuse();
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
}

void OutputFile::commit() {
  const auto fail = [&](const char* what) {
    throw InputError("could not write '" + path_ + "' (" + what + ": " + std::strerror(errno) + ")", option_);
  };
  const std::string text = buffer_.str();
  for (std::size_t written = 0; written < text.size();) {
    const ssize_t n = ::write(fd_, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("write");
    written += static_cast<std::size_t>(n);
  }
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close");
  if (!temporary_.empty() && ::rename(temporary_.c_str(), path_.c_str()) != 0) fail("rename");
  committed_ = true;
}

void write_output_file(const std::string& path, const std::string& text, const std::string& option) {
  OutputFile file(path, option);
  file.stream() << text;
  file.commit();
}

}  // namespace rb

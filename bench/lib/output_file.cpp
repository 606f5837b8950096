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

// What the target is when it exists and is not a regular file, after
// following a symlink (lstat, then stat): "" for none or a regular file.
std::string non_regular_kind(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISLNK(st.st_mode) && ::stat(path.c_str(), &st) != 0) return "";  // a dangling link: replaced
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISDIR(st.st_mode)) return "a folder";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

OutputFile::OutputFile(std::string path, std::string option) : path_(std::move(path)), option_(std::move(option)) {
  const auto refuse = [&] { throw InputError("cannot open '" + path_ + "' for writing", option_); };
  if (path_.empty() || path_.back() == '/') refuse();
  // only regular files are written: never a FIFO (open would hang with no
  // reader), a device or what a planted symlink points at
  if (const std::string kind = non_regular_kind(path_); !kind.empty())
    throw InputError("'" + path_ + "' exists and is " + kind + "; outputs are written only to regular files", option_);
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
  if (::fsync(fd_) != 0) fail("fsync");  // the bytes on disk before the name points at them
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close");
  // the target may have become something else since it was checked
  if (const std::string kind = non_regular_kind(path_); !kind.empty()) {
    errno = EEXIST;
    fail(("the target became " + kind).c_str());
  }
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("rename");
  committed_ = true;
  std::string folder = std::filesystem::path(path_).parent_path().string();
  if (folder.empty()) folder = ".";
  if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
    ::fsync(dir);  // the rename itself on disk
    ::close(dir);
  }
}

void write_output_file(const std::string& path, const std::string& text, const std::string& option) {
  OutputFile file(path, option);
  file.stream() << text;
  file.commit();
}

}  // namespace rb

#include "bench/lib/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>

#include "bench/lib/temporary_registry.hpp"
#include "problems/input_error.hpp"
#include "problems/native_cache.hpp"

namespace rb {

namespace {

std::atomic<unsigned long> temporary_counter{0};

// ".NAME.tmp.PID.N.T" in the target's folder: unique per process and call,
// hidden, and on the same file system so that rename is atomic.
std::string temporary_name(const std::string& name) {
  const auto nanoseconds = std::chrono::steady_clock::now().time_since_epoch().count();
  // appended piece by piece: "." + std::string(...) trips GCC 12's false -Wrestrict
  std::string temporary = ".";
  temporary += name;
  temporary += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(temporary_counter++) + "." +
               std::to_string(nanoseconds % 1000000007);
  return temporary;
}

// What name in the folder is when it exists and is not a regular file,
// after following a symlink (fstatat without, then with): "" for none or a
// regular file.
std::string non_regular_kind(int folder, const std::string& name) {
  struct stat st {};
  if (::fstatat(folder, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return "";
  if (S_ISLNK(st.st_mode) && ::fstatat(folder, name.c_str(), &st, 0) != 0) return "";  // a dangling link: replaced
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISDIR(st.st_mode)) return "a folder";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

OutputFile::OutputFile(std::string path, std::string option) : path_(std::move(path)), option_(std::move(option)) {
  const auto refuse = [&](const std::string& why = "") {
    throw InputError("cannot open '" + path_ + "' for writing" + (why.empty() ? "" : " (" + why + ")"), option_);
  };
  if (path_.empty() || path_.back() == '/') refuse();
  const std::filesystem::path p(path_);
  name_ = p.filename().string();
  if (name_ == "." || name_ == "..") refuse();
  std::string folder = p.parent_path().string();
  while (folder.size() > 1 && folder.back() == '/') folder.pop_back();  // a trailing '/' would follow a link
  // push_back, not = ".": GCC 12 warns falsely (-Wrestrict)
  if (folder.empty()) folder.push_back('.');
  // everything below goes through this descriptor: a folder renamed or
  // replaced by a link after this open is never written into
  folder_fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (folder_fd_ < 0) {
    struct stat st {};
    const bool link = ::lstat(folder.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
    refuse(link ? "its folder '" + folder + "' is a symbolic link" : "");
  }
  // only regular files are written: never a FIFO (open would hang with no
  // reader), a device or what a planted symlink points at
  if (const std::string kind = non_regular_kind(folder_fd_, name_); !kind.empty())
    throw InputError("'" + path_ + "' exists and is " + kind + "; outputs are written only to regular files", option_);
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    temporary_ = temporary_name(name_);
    // registered before it exists, so that no signal finds it unnamed
    slot_ = register_temporary(folder_fd_, temporary_.c_str());
    // 0666 less the umask: the mode a plain open would give the file
    fd_ = ::openat(folder_fd_, temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ >= 0) break;
    const int error = errno;
    unregister_temporary(slot_);
    slot_ = -1;
    if (error != EEXIST) break;
  }
  if (fd_ < 0) {
    temporary_.clear();
    refuse();
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlinkat(folder_fd_, temporary_.c_str(), 0);
  unregister_temporary(slot_);  // before the descriptor the table names is closed
  if (folder_fd_ >= 0) ::close(folder_fd_);
}

void OutputFile::commit() {
  const auto fail = [&](const char* what) {
    throw InputError("could not write '" + path_ + "' (" + what + ": " + std::strerror(errno) + ")", option_);
  };
  const std::string text = buffer_.str();
  if (!write_all(fd_, text)) fail("write");
  if (::fsync(fd_) != 0) fail("fsync");  // the bytes on disk before the name points at them
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close");
  // the target may have become something else since it was checked
  if (const std::string kind = non_regular_kind(folder_fd_, name_); !kind.empty()) {
    errno = EEXIST;
    fail(("the target became " + kind).c_str());
  }
  if (::renameat(folder_fd_, temporary_.c_str(), folder_fd_, name_.c_str()) != 0) fail("rename");
  committed_ = true;
  unregister_temporary(slot_);
  slot_ = -1;
  ::fsync(folder_fd_);  // the rename itself on disk
}

void write_output_file(const std::string& path, const std::string& text, const std::string& option) {
  OutputFile file(path, option);
  file.stream() << text;
  file.commit();
}

}  // namespace rb

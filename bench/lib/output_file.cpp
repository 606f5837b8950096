#include "bench/lib/output_file.hpp"

#include <fcntl.h>
#include <linux/magic.h>
#include <sys/stat.h>
#include <sys/statfs.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "bench/lib/temporary_registry.hpp"
#include "problems/input_error.hpp"
#include "problems/native_cache.hpp"
#include "problems/safe_path.hpp"

namespace rb {

namespace {

std::atomic<unsigned long> temporary_counter{0};

// "NAME.PID.N.T": unique per process and call.
std::string unique_name(const std::string& name) {
  const auto nanoseconds = std::chrono::steady_clock::now().time_since_epoch().count();
  // appended piece by piece: "." + std::string(...) trips GCC 12's false -Wrestrict
  std::string unique = name;
  unique += "." + std::to_string(::getpid()) + "." + std::to_string(temporary_counter++) + "." +
            std::to_string(nanoseconds % 1000000007);
  return unique;
}

// ".NAME.tmp.PID.N.T" in the target's folder: hidden, and on the same file
// system so that rename is atomic.
std::string temporary_name(const std::string& name) { return unique_name("." + name + ".tmp"); }

bool on_proc(int folder) {
  struct statfs fs {};
  return ::fstatfs(folder, &fs) == 0 && fs.f_type == PROC_SUPER_MAGIC;
}

// Whether name in folder is in /proc or a symbolic link that leads there,
// link by link (/dev/stdout -> /proc/self/fd/1, /dev/fd/1 through the
// link /dev/fd): a descriptor's magic link, which must never be renamed
// over. A hop through a link the path rule does not follow ends the search:
// the rename then replaces only the link in the target's folder.
bool leads_into_proc(int folder, std::string name) {
  UniqueFd held;
  int dir = folder;
  for (int hop = 0; hop <= kMaxLinkHops; ++hop) {
    if (on_proc(dir)) return true;
    struct stat st {};
    if (::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISLNK(st.st_mode)) return false;
    const std::string target = read_link(dir, name);
    const std::size_t slash = target.find_last_of('/');
    if (target.empty() || slash == target.size() - 1) return false;
    std::string parent = slash == std::string::npos ? "." : target.substr(0, slash);
    if (parent.empty()) parent = "/";
    OpenedFolder next = open_folder(parent, MissingFolders::fail, 0777, dir);
    if (!next) return false;
    held = std::move(next.fd);
    dir = held.get();
    name = slash == std::string::npos ? target : target.substr(slash + 1);
  }
  return false;
}

bool is_standard_output(const struct stat& st) {
  struct stat out {};
  return ::fstat(STDOUT_FILENO, &out) == 0 && out.st_dev == st.st_dev && out.st_ino == st.st_ino;
}

std::string kind_of(const struct stat& st) {
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISDIR(st.st_mode)) return "a folder";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

// What name in the folder is when it may not be replaced by a regular file
// ("" when it may: missing, a regular file, a link to one, a dangling link),
// looked at without writing; standard_output set for a link into /proc's
// descriptors to what descriptor 1 is.
std::string unreplaceable_kind(int folder, const std::string& name, bool& standard_output) {
  standard_output = false;
  struct stat st {};
  if (::fstatat(folder, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
    return on_proc(folder) ? "not a regular file" : "";
  if (S_ISREG(st.st_mode) && !on_proc(folder)) return "";
  if (!S_ISLNK(st.st_mode)) return kind_of(st);
  const bool descriptor = leads_into_proc(folder, name);
  if (::fstatat(folder, name.c_str(), &st, 0) != 0)  // a dangling link: replaced, unless a closed descriptor's
    return descriptor ? "a link to a file descriptor that is not open" : "";
  if (descriptor && is_standard_output(st)) {
    standard_output = true;
    return "";
  }
  if (!S_ISREG(st.st_mode)) return kind_of(st);
  return descriptor ? "a link to a file descriptor other than standard output" : "";
}

// The folders a lost output is kept in, in order.
std::vector<std::string> keeping_folders() {
  std::vector<std::string> folders;
  if (const char* tmpdir = std::getenv("TMPDIR"); tmpdir && tmpdir[0] == '/') folders.push_back(tmpdir);
  for (const char* fixed : {"/tmp", "/var/tmp"})
    if (folders.empty() || folders.front() != fixed) folders.push_back(fixed);
  return folders;
}

}  // namespace

OutputFile::OutputFile(std::string path, std::string option, IfLost if_lost)
    : path_(std::move(path)), option_(std::move(option)), if_lost_(if_lost) {
  const auto refuse = [&](const std::string& why = "") {
    throw InputError("cannot open '" + path_ + "' for writing" + (why.empty() ? "" : " (" + why + ")"), option_);
  };
  if (path_.empty() || path_.back() == '/') refuse();
  const std::filesystem::path p(path_);
  name_ = p.filename().string();
  if (name_ == "." || name_ == "..") refuse();
  std::string folder = p.parent_path().string();
  // push_back, not = ".": GCC 12 warns falsely (-Wrestrict)
  if (folder.empty()) folder.push_back('.');
  // everything below goes through this descriptor: a folder renamed or
  // replaced by a link after this open is never written into
  OpenedFolder opened = open_folder(folder);
  if (!opened) refuse(opened.refused);
  folder_fd_ = opened.fd.release();
  // only regular files are written: never a FIFO (open would hang with no
  // reader), a device or what a planted symlink points at
  if (const std::string kind = unreplaceable_kind(folder_fd_, name_, to_standard_output_); !kind.empty())
    throw InputError("'" + path_ + "' exists and is " + kind + "; outputs are written only to regular files", option_);
  if (to_standard_output_) return;  // no temporary: commit writes to descriptor 1
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
  if (!committed_) remove_temporary();
  if (folder_fd_ >= 0) ::close(folder_fd_);
}

void OutputFile::remove_temporary() {
  if (!temporary_.empty()) ::unlinkat(folder_fd_, temporary_.c_str(), 0);
  temporary_.clear();
  unregister_temporary(slot_);  // before the descriptor the table names is closed
  slot_ = -1;
}

void OutputFile::write_and_rename(const std::string& text) {
  const auto fail = [&](const char* what) {
    throw InputError("could not write '" + path_ + "' (" + what + ": " + std::strerror(errno) + ")", option_);
  };
  if (to_standard_output_) {
    std::fflush(stdout);  // what was printed before comes before
    if (!write_all(STDOUT_FILENO, text)) fail("write");
    return;
  }
  if (!write_all(fd_, text)) fail("write");
  if (::fsync(fd_) != 0) fail("fsync");  // the bytes on disk before the name points at them
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close");
  // the target may have become something else since it was checked
  bool standard_output = false;
  if (const std::string kind = unreplaceable_kind(folder_fd_, name_, standard_output);
      !kind.empty() || standard_output) {
    errno = EEXIST;
    fail(("the target became " + (kind.empty() ? std::string("a link to standard output") : kind)).c_str());
  }
  if (::renameat(folder_fd_, temporary_.c_str(), folder_fd_, name_.c_str()) != 0) fail("rename");
  temporary_.clear();
  unregister_temporary(slot_);
  slot_ = -1;
  ::fsync(folder_fd_);  // the rename itself on disk
}

void OutputFile::commit() {
  const std::string text = buffer_.str();
  try {
    write_and_rename(text);
    committed_ = true;
  } catch (const InputError& e) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    remove_temporary();  // its blocks freed before a copy is kept
    if (if_lost_ == IfLost::discard) throw;
    throw InputError(e.message() + "; " + keep_copy(text), option_);
  }
}

std::string OutputFile::keep_copy(const std::string& text) const {
  // a name of the target's, cut so that the whole stays within NAME_MAX
  const std::string name = "rollbench-kept-" + name_.substr(0, 150);
  std::string tried;
  for (const std::string& place : keeping_folders()) {
    tried += (tried.empty() ? "" : ", ") + place;
    const OpenedFolder folder = open_folder(place);
    if (!folder) continue;
    for (int attempt = 0; attempt < 100; ++attempt) {
      const std::string kept = unique_name(name);
      const UniqueFd fd(
          ::openat(folder.fd.get(), kept.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
      if (!fd) {
        if (errno == EEXIST) continue;
        break;
      }
      if (write_all(fd.get(), text) && ::fsync(fd.get()) == 0) {
        ::fsync(folder.fd.get());
        return "its content is kept in '" + (std::filesystem::path(place) / kept).string() + "'";
      }
      ::unlinkat(folder.fd.get(), kept.c_str(), 0);
      break;
    }
  }
  return "its content could not be kept elsewhere either (tried " + tried + ")";
}

void write_output_file(const std::string& path, const std::string& text, const std::string& option, IfLost if_lost) {
  OutputFile file(path, option, if_lost);
  file.stream() << text;
  file.commit();
}

}  // namespace rb

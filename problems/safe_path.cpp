// Folders walked component by component, following only links of this
// user or root (safe_path.hpp).
#include "problems/safe_path.hpp"

#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

namespace rb {

namespace {

// The components of path, last first (a stack: a followed link's target is
// pushed on top of what is left); "" and "." are left out.
void push_components(const std::string& path, std::vector<std::string>& stack) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    std::size_t end = path.find('/', begin);
    if (end == std::string::npos) end = path.size();
    if (std::string part = path.substr(begin, end - begin); !part.empty() && part != ".") parts.push_back(part);
    begin = end + 1;
  }
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) stack.push_back(*it);
}

std::string joined(const std::string& folder, const std::string& name) {
  if (folder.empty()) return name;
  return folder.back() == '/' ? folder + name : folder + "/" + name;
}

constexpr int kWalk = O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC;

}  // namespace

bool may_follow_link(uid_t link_owner) { return link_owner == ::geteuid() || link_owner == 0; }

std::string OpenedFolder::why() const { return refused.empty() ? std::string(std::strerror(error)) : refused; }

std::string read_link(int folder, const std::string& name) {
  char buffer[PATH_MAX];
  const ssize_t n = ::readlinkat(folder, name.c_str(), buffer, sizeof buffer);
  if (n < 0) return {};
  if (static_cast<std::size_t>(n) >= sizeof buffer) {
    errno = ENAMETOOLONG;
    return {};
  }
  if (n == 0) errno = ENOENT;
  return std::string(buffer, static_cast<std::size_t>(n));
}

OpenedFolder open_folder(const std::string& path, MissingFolders missing, mode_t mode, int start) {
  OpenedFolder result;
  const auto fail = [&](int error) {
    result.fd = UniqueFd();
    result.error = error;
    return std::move(result);
  };
  if (path.empty()) return fail(ENOENT);
  const bool absolute = path.front() == '/';
  UniqueFd dir(absolute ? ::open("/", kWalk) : ::openat(start, ".", kWalk));
  if (!dir) return fail(errno);
  std::string shown = absolute ? "/" : "";  // the path walked so far, for messages
  std::vector<std::string> pending;
  push_components(path, pending);
  int hops = 0;
  while (!pending.empty()) {
    const std::string name = std::move(pending.back());
    pending.pop_back();
    UniqueFd next(::openat(dir.get(), name.c_str(), kWalk));
    if (!next && errno == ENOENT && missing == MissingFolders::make) {
      // EEXIST: made meanwhile by another process, or a dangling link (found below)
      if (::mkdirat(dir.get(), name.c_str(), mode) != 0 && errno != EEXIST) return fail(errno);
      next = UniqueFd(::openat(dir.get(), name.c_str(), kWalk));
    }
    if (next) {
      dir = std::move(next);
      shown = joined(shown, name);
      continue;
    }
    const int error = errno;
    struct stat link {};
    if (::fstatat(dir.get(), name.c_str(), &link, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISLNK(link.st_mode))
      return fail(error);
    if (!may_follow_link(link.st_uid)) {
      struct stat folder {};
      const std::string folder_owner = ::fstat(dir.get(), &folder) == 0 ? std::to_string(folder.st_uid) : "?";
      result.refused = "'" + joined(shown, name) + "' is a symbolic link owned by uid " + std::to_string(link.st_uid) +
                       " in a folder owned by uid " + folder_owner + "; not followed";
      return fail(0);
    }
    if (++hops > kMaxLinkHops) return fail(ELOOP);
    const std::string target = read_link(dir.get(), name);
    if (target.empty()) return fail(errno);
    if (target.front() == '/') {
      dir = UniqueFd(::open("/", kWalk));
      if (!dir) return fail(errno);
      shown = "/";
    }
    push_components(target, pending);
  }
  // the folder itself readable (fsync, a folder's listing); O_PATH serves
  // openat, renameat and unlinkat where only search is allowed
  if (UniqueFd readable(::openat(dir.get(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC)); readable)
    dir = std::move(readable);
  result.fd = std::move(dir);
  return result;
}

}  // namespace rb

#pragma once
// Folders opened by a path without following what others own (issue 57):
// every output, cache entry and cache folder rollbench writes is reached
// through open_folder.
//
// The path is walked one component at a time from "/" (an absolute path)
// or the starting folder (a relative one), each with openat(O_PATH |
// O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC) on the folder opened last: a
// component swapped after it was opened is never reached. A component that
// is a symbolic link is followed only when the link is owned by this
// process's effective uid or by root (uid 0), since only then can no one
// else have pointed it elsewhere; its target is walked again by the same
// rule, at most kMaxLinkHops links in all. Any other link is refused,
// naming it: "'S/nob/link' is a symbolic link owned by uid 65534 in a
// folder owned by uid 65534; not followed". So /tmp itself, /dev/stdout ->
// /proc/self/fd/1 and /proc/self (root's links) are followed for everyone.
//
// This is stricter than the kernel's fs.protected_symlinks, which also
// follows a link whose owner owns the folder it sits in: a user who owns a
// folder inside a shared one (S/nob, nobody's, in the sticky S) could then
// point S/nob/link at /root and have root's output land there.
#include <fcntl.h>
#include <sys/types.h>

#include <string>

#include "problems/native_cache.hpp"  // UniqueFd

namespace rb {

inline constexpr int kMaxLinkHops = 40;  // the kernel's MAXSYMLINKS

// Whether a symbolic link owned by uid may be followed (see above).
bool may_follow_link(uid_t link_owner);

enum class MissingFolders { fail, make };

struct OpenedFolder {
  UniqueFd fd;          // the folder, O_RDONLY (O_PATH when it can be searched but not read)
  int error = 0;        // the errno of a failed open or mkdir on the way (ENOENT, EACCES, ENOTDIR, ELOOP)
  std::string refused;  // why a link on the way was not followed; then fd is empty
  explicit operator bool() const { return static_cast<bool>(fd); }
  // refused, or the error's text
  std::string why() const;
};

// Opens path as a folder by the rule above; relative paths start at start
// (AT_FDCWD: the working folder). With MissingFolders::make, each missing
// component is made with mkdirat(mode, less the umask), as mkdir -p does.
OpenedFolder open_folder(const std::string& path, MissingFolders missing = MissingFolders::fail, mode_t mode = 0777,
                         int start = AT_FDCWD);

// The text of the symbolic link name in folder; empty (errno set) when it
// cannot be read.
std::string read_link(int folder, const std::string& name);

}  // namespace rb

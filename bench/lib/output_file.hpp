#pragma once
// Every file rollbench writes (report, merge and score JSON, trajectory and
// landscape CSV, cached references) goes through OutputFile: the bytes go
// to a new file next to the target (opened O_CREAT | O_EXCL | O_NOFOLLOW
// under a unique name) and commit() renames it onto the target. A run that
// fails before commit leaves an existing file as it was and no partial one:
// the temporary file is removed, also on every terminating signal that can
// be caught (bench/lib/temporary_registry.hpp). The temporary is fsync'ed
// before the rename and the folder after it.
//
// The path rule (issue 57; problems/safe_path.hpp): the target's folder is
// opened once, component by component without following a symbolic link
// unless it is this user's or root's (another's is refused, naming it:
// "'S/nob/link' is a symbolic link owned by uid 65534 in a folder owned by
// uid 65534; not followed"), and the temporary, the checks and the rename go
// through that descriptor (openat, fstatat, renameat), with the target's
// last component as the name: nothing is created outside the folder. The
// last component itself is never followed for writing:
// - missing, a regular file, a link to a regular file or a dangling link:
//   replaced by the new file (a link is replaced, its target untouched);
// - a link that leads into /proc's descriptors (/dev/stdout, /dev/fd/1,
//   /proc/self/fd/1) to what standard output is: the bytes are written to
//   descriptor 1 as a stream (so `--out /dev/stdout > x.csv` fills x.csv),
//   the link left as it is; a link to another descriptor is refused;
// - anything else that is not a regular file (a FIFO, a device, a folder, a
//   socket, or a link to one): refused with an InputError naming the path.
// Output goes only to regular files, and a rename never replaces anything
// but a regular file or a link.
//
// A commit that fails (a full disk: ENOSPC at write, fsync, close or rename)
// with IfLost::keep_elsewhere writes the bytes to a new file
// `rollbench-kept-NAME.PID.N.T` (O_CREAT | O_EXCL | O_NOFOLLOW, mode 0600)
// in $TMPDIR, else /tmp, else /var/tmp (each opened by the path rule), and
// the error says where; the error stays an error.
#include <sstream>
#include <string>

namespace rb {

// What a failed commit does with the bytes: lose them (a cache entry: only
// slower next time) or keep them elsewhere (a sweep's report).
enum class IfLost { discard, keep_elsewhere };

class OutputFile {
 public:
  // Opens the temporary file at once, so that an unwritable place is an
  // InputError under option ("cannot open 'PATH' for writing") before any
  // work is done; a folder behind a link not followed is refused there too
  // ("cannot open 'PATH' for writing ('L' is a symbolic link ...)").
  OutputFile(std::string path, std::string option, IfLost if_lost = IfLost::discard);
  ~OutputFile();  // removes the temporary file unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return buffer_; }
  // Writes what stream() holds and renames it onto the path (or writes it
  // to standard output); InputError under the option ("could not write
  // 'PATH' (reason)") otherwise, with "; its content is kept in 'F'" when
  // kept elsewhere.
  void commit();

 private:
  void write_and_rename(const std::string& text);
  void remove_temporary();
  std::string keep_copy(const std::string& text) const;

  std::string path_, option_, name_, temporary_;
  IfLost if_lost_;
  int folder_fd_ = -1, fd_ = -1;
  int slot_ = -1;  // in the signal handler's table
  bool committed_ = false;
  bool to_standard_output_ = false;
  std::ostringstream buffer_;
};

// The whole of text written to path as OutputFile does.
void write_output_file(const std::string& path, const std::string& text, const std::string& option,
                       IfLost if_lost = IfLost::discard);

}  // namespace rb

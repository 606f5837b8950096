#pragma once
// Every file rollbench writes (report, merge and score JSON, trajectory and
// landscape CSV, cached references) goes through OutputFile: the bytes go
// to a new file next to the target (opened O_CREAT | O_EXCL | O_NOFOLLOW
// under a unique name) and commit() renames it onto the target. A run that
// fails before commit leaves an existing file as it was and no partial one:
// the temporary file is removed, also on SIGINT, SIGTERM or SIGHUP
// (bench/lib/temporary_registry.hpp). The temporary is fsync'ed before the
// rename and the folder after it. The target's folder is opened once
// (O_DIRECTORY | O_NOFOLLOW: a folder that is a symlink is refused) and the
// temporary, the checks and the rename go through that descriptor (openat,
// fstatat, renameat), with the target's last component as the name: nothing
// is created outside the folder. A target that exists and is not a regular
// file (a FIFO, a device, a folder, or a symlink to one) is refused with an
// InputError naming the path: output goes only to regular files.
#include <sstream>
#include <string>

namespace rb {

class OutputFile {
 public:
  // Opens the temporary file at once, so that an unwritable place is an
  // InputError under option ("cannot open 'PATH' for writing") before any
  // work is done.
  OutputFile(std::string path, std::string option);
  ~OutputFile();  // removes the temporary file unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return buffer_; }
  // Writes what stream() holds and renames it onto the path; InputError
  // under the option ("could not write 'PATH' (reason)") otherwise.
  void commit();

 private:
  std::string path_, option_, name_, temporary_;
  int folder_fd_ = -1, fd_ = -1;
  int slot_ = -1;  // in the signal handler's table
  bool committed_ = false;
  std::ostringstream buffer_;
};

// The whole of text written to path as OutputFile does.
void write_output_file(const std::string& path, const std::string& text, const std::string& option);

}  // namespace rb

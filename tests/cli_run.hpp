#pragma once
// Runs this build's rollbench as a user does, for the command-line tests:
// the exit status and what it wrote on standard output and standard error.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rb::testing {

struct CliOutcome {
  int code;  // exit status; -1 when it did not exit normally
  std::string out, err;
};

// The test process's own folder in the temporary folder (mkdtemp), made on
// first use and removed with what the tests wrote there when the process
// exits: each test leaves its outputs behind otherwise, some 160 files in
// /tmp a run of the suite. Removed only by the process that made it, so that
// a forked child's exit does not take it away from under its parent.
class CliTempFolder {
 public:
  CliTempFolder() : owner_(::getpid()) {
    std::string name = (std::filesystem::temp_directory_path() / "rb-cli-run-XXXXXX").string();
    if (!::mkdtemp(name.data())) throw std::runtime_error("cannot make a folder like " + name);
    path_ = name;
  }
  ~CliTempFolder() {
    std::error_code ignored;
    if (::getpid() == owner_) std::filesystem::remove_all(path_, ignored);
  }
  CliTempFolder(const CliTempFolder&) = delete;
  CliTempFolder& operator=(const CliTempFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  pid_t owner_;
  std::filesystem::path path_;
};

// A path in the temporary folder, unique to this test process.
inline std::filesystem::path cli_temp_file(const std::string& name) {
  static const CliTempFolder folder;
  return folder.path() / name;
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `rollbench ARGS` through the shell (args are not quoted: test paths only).
inline CliOutcome run_rollbench(const std::string& args) {
  const std::filesystem::path out = cli_temp_file("stdout"), err = cli_temp_file("stderr");
  const std::string command = std::string(RB_ROLLBENCH_EXE) + " " + args + " > " + out.string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

}  // namespace rb::testing

#pragma once
// Runs this build's rollbench as a user does, for the command-line tests:
// the exit status and what it wrote on standard output and standard error.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rb::testing {

struct CliOutcome {
  int code;  // exit status; -1 when it did not exit normally
  std::string out, err;
};

// A path in the temporary folder, unique to this test process.
inline std::filesystem::path cli_temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("rb-cli-run-" + std::to_string(::getpid()) + "-" + name);
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

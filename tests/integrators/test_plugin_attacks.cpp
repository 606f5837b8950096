// The five hostile plug-ins of issue 32 (examples/test_steppers.c): each
// lives in its child process entirely (integrators/steppers/isolated_run.hpp)
// and none of them takes rollbench down, hangs it, floods its memory, runs
// its atexit handlers or leaves a process behind.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "tests/cli_run.hpp"
#include "tests/example_steppers.hpp"

namespace rb {
namespace {

using testing::cli_temp_file;
using testing::example_stepper;
using testing::run_rollbench;

std::string trajectory_with(const std::string& name, const std::string& library, const std::string& out,
                            const std::string& timeout_s = "20") {
  return "trajectory valley-sideways --integrator " + name + " --h 0.0625 --stepper-timeout " + timeout_s + " --out " +
         out + " --stepper " + example_stepper(library);
}

TEST(PluginAttacks, AConstructorRaisingSigsegvIsALoadErrorNotACrashOfRollbench) {
  const testing::CliOutcome o = run_rollbench("list --stepper " + example_stepper("ctor_segv_stepper"));
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 'stepper': '" + example_stepper("ctor_segv_stepper") +
                       "': loading it (in a child process) crashed: its process was killed by signal 11 (SIGSEGV: "
                       "Segmentation fault)\n");
}

TEST(PluginAttacks, InfoReturningNullOnItsSecondCallIsAskedOnceAndRuns) {
  const std::filesystem::path csv = cli_temp_file("info-null.csv");
  const testing::CliOutcome listed = run_rollbench("list --stepper " + example_stepper("info_null_stepper"));
  EXPECT_EQ(listed.code, 0) << listed.err;
  EXPECT_NE(listed.out.find("info-null-stepper"), std::string::npos) << listed.out;
  const testing::CliOutcome o = run_rollbench(trajectory_with("info-null-stepper", "info_null_stepper", csv.string()));
  EXPECT_EQ(o.code, 0) << o.err;
}

TEST(PluginAttacks, AForkingPluginHoldingThePipeIsOkAndItsGrandchildDoesNotOutliveTheRun) {
  const std::filesystem::path csv = cli_temp_file("forks.csv"), pid_file = cli_temp_file("grandchild.pid");
  std::filesystem::remove(pid_file);
  ::setenv("RB_TEST_GRANDCHILD_PID_FILE", pid_file.c_str(), 1);
  const testing::CliOutcome o = run_rollbench(trajectory_with("forks-stepper", "forks_stepper", csv.string()));
  ::unsetenv("RB_TEST_GRANDCHILD_PID_FILE");
  EXPECT_EQ(o.code, 0) << o.err;  // not "timeout": the run's end is the child's exit, not the pipe's
  std::ifstream in(pid_file);
  int pid = 0;
  ASSERT_TRUE(in >> pid) << "the grandchild wrote no pid";
  // gone, or a zombie waiting for its new parent to reap it: not running
  // SIGKILL is delivered at once but the exit completes when the kernel schedules it: allow it 2 s to die
  std::string state;
  for (int tries = 0; tries < 200; ++tries) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string field, name;
    if (!(stat >> field >> name >> state) || state == "Z") {
      state = "gone";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(state, "gone") << "the grandchild " << pid << " is still running";
}

TEST(PluginAttacks, APluginWriting400MibIsKilledAtTheAnswerLimit) {
  const std::filesystem::path csv = cli_temp_file("flood.csv");
  // the answer limit, not the clock, must stop it: a timeout far beyond the
  // seconds 128 MiB take through a pipe under a sanitizer on a loaded machine
  const testing::CliOutcome o = run_rollbench(trajectory_with("flood-stepper", "flood_stepper", csv.string(), "300"));
  EXPECT_EQ(o.code, 3);
  EXPECT_EQ(o.err,
            "rollbench: run stopped early at t = 0: crashed: stepper 'flood-stepper' crashed: its process sent more "
            "than 134217728 bytes (the limit of an answer) and was killed; its state and cost are lost\n");
}

// The largest resident size (KiB) of rollbench and what it waited for
// (wait4) over one plug-in trajectory; `code` is its exit status.
long max_rss_of_trajectory(const std::string& name, const std::string& library, int& code) {
  const std::string csv = cli_temp_file(name + "-rss.csv").string(), path = example_stepper(library);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(RB_ROLLBENCH_EXE, RB_ROLLBENCH_EXE, "trajectory", "valley-sideways", "--integrator", name.c_str(), "--h",
            "0.0625", "--stepper-timeout", "20", "--out", csv.c_str(), "--stepper", path.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage {};
  if (::wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status)) return -1;
  code = WEXITSTATUS(status);
  return usage.ru_maxrss;
}

// 42e9db5 read the pipe without a limit: 541 MB for a 400 MiB write. Against
// a well-behaved plug-in's run measured here (so a sanitizer's overhead is in
// both), the flood adds less than the 400 MiB it wrote: it was never held
// whole, only up to the answer limit (128 MiB) and the string's growth.
TEST(PluginAttacks, APluginWriting400MibLeavesTheParentsMemoryBounded) {
  int baseline_code = -1, flood_code = -1;
  const long baseline = max_rss_of_trajectory("midpoint-plugin", "midpoint_stepper", baseline_code);
  const long flood = max_rss_of_trajectory("flood-stepper", "flood_stepper", flood_code);
  ASSERT_GT(baseline, 0);
  ASSERT_GT(flood, 0);
  EXPECT_EQ(baseline_code, 0);
  EXPECT_EQ(flood_code, 3);  // the run stopped: crashed
  EXPECT_LT(flood - baseline, 400L * 1024 - 16L * 1024) << "KiB above the baseline's " << baseline << " KiB";
}

TEST(PluginAttacks, APluginCallingExitLeavesWithoutTheParentsAtexitHandlers) {
  const std::filesystem::path csv = cli_temp_file("exit.csv");
  const testing::CliOutcome o = run_rollbench(trajectory_with("exit-stepper", "exit_stepper", csv.string()));
  EXPECT_EQ(o.code, 3);
  EXPECT_EQ(o.err,
            "rollbench: run stopped early at t = 0: crashed: stepper 'exit-stepper' crashed: it called exit() in its "
            "process; its state and cost are lost\n");
}

}  // namespace
}  // namespace rb

#pragma once
// A run in a child process, for code the suite does not trust (a --stepper
// plug-in): fork, the child integrates and sends its RunResult back over a
// pipe, the parent waits at most a wall-clock limit. A child that dies (a
// signal: SIGSEGV, SIGABRT, ...; an exit without a whole result) is the
// status "crashed", one still running at the limit is killed by its pid
// and the status "timeout"; the parent process and the rest of a sweep go on.
//
// The child is its own process group (the parent kills the whole group
// when the child ends and on timeout: a grandchild does not outlive the
// run), dies with the parent (PR_SET_PDEATHSIG), and its end is the
// child's own exit (a pidfd), not the pipe's: a grandchild holding the
// pipe open does not turn a finished run into a timeout. The parent reads
// at most kMaxIsolatedAnswerBytes; a child sending more is killed and its
// run "crashed". A child calling exit() leaves by _exit before any
// handler of the parent runs (atexit order) and is "crashed" too.
//
// What is timed: the child measures its own integration (steady clock,
// right around body()) and returns it as RunResult::solve_seconds, so that
// fork, pipe and result transfer are not charged to the method; with
// warm_up it first runs body() once untimed, since a forked child's first
// run also pays for copying every page it writes (about 60 us a run, see
// docs/design.md).
//
// The child restores the default action of the crash signals (SIGSEGV,
// SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS: a sanitizer's handler
// would turn them into an exit code), sets no core file, and
// runs only body() and ends with _exit: no atexit handlers, no
// destructors of the parent's objects, no stdio flush of the parent's
// buffers. The parent flushes stdout and stderr before fork so nothing is
// written twice. Forking from a threaded sweep is safe for this body: it
// only computes and allocates (glibc resets malloc's locks in the child).
#include <cstddef>
#include <functional>
#include <string>

#include "integrators/integrator.hpp"

namespace rb {

// The default wall-clock limit of one isolated run, in seconds: far above
// any run of the shipped presets (the slowest plug-in run of the full
// preset takes seconds), short enough that a hanging plug-in costs minutes.
inline constexpr double kDefaultIsolatedWallLimit = 300.0;

// The most bytes the parent reads from one child (128 MiB: a result of
// about a million output points of 14 doubles).
inline constexpr std::size_t kMaxIsolatedAnswerBytes = std::size_t{128} << 20;

// How a child ended: its wait status, whether it was killed at the limit
// or for sending more than the limit, and the bytes it sent.
struct ChildOutcome {
  int wait_status = 0;
  bool timed_out = false;
  bool too_long = false;
  std::string answer;
};

// Runs answer_of in a child process (as described above) and returns what
// it sent; throws std::runtime_error naming who when no pipe or fork.
ChildOutcome run_in_child(const std::function<std::string()>& answer_of, const std::string& who, double wall_limit_s,
                          std::size_t max_answer_bytes);

// Why a child that did not exit 0 (or was killed) gave no answer, as a
// sentence after the name: "crashed: its process was killed by signal 11
// (SIGSEGV: Segmentation fault)", "was still running after ...".
std::string child_failure_text(const ChildOutcome& outcome, double wall_limit_s, std::size_t max_answer_bytes);

// Runs body in a child process and returns its result; who names the
// method in the messages ("stepper 'x'"), start is the state a crashed
// run reports as its last valid one (the child's own is lost with it).
// An exception thrown by body is thrown again here: an InputError with
// its key, anything else as a std::runtime_error with its what().
// warm_up: run body once untimed in the child first (RunOptions::warm_up).
RunResult run_isolated(const std::function<RunResult()>& body, const std::string& who, double wall_limit_s,
                       const FlatState& start, bool warm_up = false);

}  // namespace rb

#include "integrators/steppers/isolated_run.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "problems/input_error.hpp"

namespace rb {

namespace {

// What the child sends: a tag, the payload, and the magic again at the
// end, so that a result cut short by a crash is seen as such.
constexpr std::uint32_t kMagic = 0x52424952;  // "RBIR"
enum class Kind : std::uint8_t { result = 0, input_error = 1, exception = 2 };

class Writer {
 public:
  template <class T>
  void put(const T& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void put_text(const std::string& text) {
    put<std::uint64_t>(text.size());
    bytes.append(text);
  }
  void put_state(const FlatState& y) {
    bytes.append(reinterpret_cast<const char*>(y.data()), sizeof(double) * y.size());
  }
  std::string bytes;
};

// Reads what Writer wrote; false once anything is short or out of place.
class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  bool get(T& value) {
    if (bytes_.size() - at_ < sizeof value) return false;
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return true;
  }
  bool get_text(std::string& text) {
    std::uint64_t size = 0;
    if (!get(size) || bytes_.size() - at_ < size) return false;
    text.assign(bytes_, at_, size);
    at_ += size;
    return true;
  }
  bool get_state(FlatState& y) {
    const std::size_t size = sizeof(double) * y.size();
    if (bytes_.size() - at_ < size) return false;
    std::memcpy(y.data(), bytes_.data() + at_, size);
    at_ += size;
    return true;
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

void put_result(Writer& w, const RunResult& r) {
  w.put(static_cast<std::int32_t>(r.status));
  w.put_text(r.message);
  w.put(r.stop_time);
  w.put_state(r.final_state);
  for (const long count : {r.cost.steps, r.cost.rejected, r.cost.rhs_evals, r.cost.jacobian_evals, r.cost.exp_evals,
                           r.cost.dexpinv_evals, r.cost.validity_checks})
    w.put(static_cast<std::int64_t>(count));
  w.put<std::uint64_t>(r.output.t.size());
  for (std::size_t i = 0; i < r.output.t.size(); ++i) {
    w.put(r.output.t[i]);
    w.put_state(r.output.y[i]);
  }
  w.put(r.solve_seconds);
}

bool get_result(Reader& in, RunResult& r) {
  std::int32_t status = 0;
  if (!in.get(status) || status < 0 || status > static_cast<std::int32_t>(Status::error)) return false;
  r.status = static_cast<Status>(status);
  if (!in.get_text(r.message) || !in.get(r.stop_time) || !in.get_state(r.final_state)) return false;
  for (long* count : {&r.cost.steps, &r.cost.rejected, &r.cost.rhs_evals, &r.cost.jacobian_evals, &r.cost.exp_evals,
                      &r.cost.dexpinv_evals, &r.cost.validity_checks}) {
    std::int64_t value = 0;
    if (!in.get(value)) return false;
    *count = static_cast<long>(value);
  }
  std::uint64_t outputs = 0;
  if (!in.get(outputs)) return false;
  for (std::uint64_t i = 0; i < outputs; ++i) {
    double t = 0.0;
    FlatState y;
    if (!in.get(t) || !in.get_state(y)) return false;
    r.output.push(t, y);
  }
  return in.get(r.solve_seconds);
}

// The child's whole answer: the result, or the exception body() threw.
std::string child_answer(const std::function<RunResult()>& body, bool warm_up) {
  Writer w;
  w.put(kMagic);
  try {
    if (warm_up) (void)body();
    const auto start = std::chrono::steady_clock::now();
    RunResult result = body();
    result.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    w.put(Kind::result);
    put_result(w, result);
  } catch (const InputError& e) {
    w.bytes.resize(sizeof kMagic);
    w.put(Kind::input_error);
    w.put_text(e.message());
    w.put_text(e.key());
    w.put(static_cast<std::int32_t>(e.column()));
  } catch (const std::exception& e) {
    w.bytes.resize(sizeof kMagic);
    w.put(Kind::exception);
    w.put_text(e.what());
  }
  w.put(kMagic);
  return w.bytes;
}

// Where the child leaves if the plug-in calls exit(): registered after
// fork, so it runs before every handler the parent registered (atexit runs
// them in reverse order) and ends the child with a code the parent reads
// as "no whole result".
constexpr int kExitCalledCode = 113;
[[noreturn]] void leave_on_exit() { ::_exit(kExitCalledCode); }

[[noreturn]] void run_child(const std::function<std::string()>& answer_of, int out) {
  ::setpgid(0, 0);  // its own process group: the parent kills it whole
  // dies with the parent (a rollbench killed by a signal leaves no child)
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // nothing but the answer's pipe stays open: a sibling child must not
  // hold another run's pipe (its parent would wait for that child's end)
  if (out > 3) ::close_range(3, static_cast<unsigned>(out) - 1, 0);
  ::close_range(static_cast<unsigned>(out) + 1, ~0U, 0);
  std::atexit([] { leave_on_exit(); });
  std::at_quick_exit([] { leave_on_exit(); });
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);  // a crash is a status, not a core file
  // the default action for the signals of a crash, whatever handler the
  // parent has (a sanitizer's turns SIGSEGV into exit code 1): the parent
  // names the signal; and for the signals that end a process, so that the
  // parent's handlers (removing its temporaries) never run in the child
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS, SIGINT, SIGTERM, SIGHUP, SIGQUIT,
                           SIGPIPE, SIGUSR1, SIGUSR2, SIGALRM})
    std::signal(signal, SIG_DFL);
  int code = 0;
  try {
    const std::string answer = answer_of();
    for (std::size_t written = 0; written < answer.size();) {
      const ssize_t n = ::write(out, answer.data() + written, answer.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        code = 1;
        break;
      }
      written += static_cast<std::size_t>(n);
    }
  } catch (...) {
    code = 1;  // no memory for the answer: the parent sees it incomplete
  }
  ::_exit(code);
}

std::string signal_text(int signal) {
  const char* abbreviation = ::sigabbrev_np(signal);
  const char* description = ::sigdescr_np(signal);
  return "signal " + std::to_string(signal) + (abbreviation != nullptr ? std::string(" (SIG") + abbreviation : " (") +
         (description != nullptr ? std::string(": ") + description : std::string()) + ")";
}

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", seconds);
  return text;
}

}  // namespace

ChildOutcome run_in_child(const std::function<std::string()>& answer_of, const std::string& who, double wall_limit_s,
                          std::size_t max_answer_bytes) {
  int pipe_ends[2];
  if (::pipe2(pipe_ends, O_CLOEXEC) != 0)
    throw std::runtime_error(who + ": cannot make a pipe for an isolated run: " + std::strerror(errno));
  std::fflush(nullptr);  // what the parent buffered is not written again by the child
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(pipe_ends[0]);
    ::close(pipe_ends[1]);
    throw std::runtime_error(who + ": cannot fork an isolated run: " + std::strerror(error));
  }
  if (pid == 0) run_child(answer_of, pipe_ends[1]);
  ::close(pipe_ends[1]);
  ::setpgid(pid, pid);  // also here: the group exists before the parent may kill it
  ::fcntl(pipe_ends[0], F_SETFL, O_NONBLOCK);
  // the child's own end, not the pipe's: a grandchild may hold the pipe open
  const int child_fd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));

  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::duration<double>(wall_limit_s);
  ChildOutcome outcome;
  bool pipe_open = true, exited = false;
  char buffer[1 << 16];
  auto child_exited = [&] {
    siginfo_t info{};
    return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
  };
  // reads what the pipe holds now; false once the pipe ended or the answer is too long
  auto drain = [&] {
    for (;;) {
      const ssize_t n = ::read(pipe_ends[0], buffer, sizeof buffer);
      if (n > 0) {
        if (outcome.answer.size() + static_cast<std::size_t>(n) > max_answer_bytes) {
          outcome.too_long = true;
          return false;
        }
        outcome.answer.append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0) {
        return false;
      } else if (errno != EINTR) {
        return errno == EAGAIN || errno == EWOULDBLOCK;
      }
    }
  };
  while (!exited && !outcome.too_long) {
    const double left = std::chrono::duration<double>(deadline - clock::now()).count();
    if (left <= 0.0) {
      outcome.timed_out = true;
      break;
    }
    // without a pidfd (an old kernel) the loop looks at the child every 5 ms
    const double wait_ms = child_fd >= 0 ? left * 1000.0 + 1.0 : std::min(left * 1000.0 + 1.0, 5.0);
    pollfd ready[2] = {{pipe_open ? pipe_ends[0] : -1, POLLIN, 0}, {child_fd, POLLIN, 0}};
    (void)::poll(ready, 2, static_cast<int>(std::min(wait_ms, double(INT_MAX))));
    if (pipe_open && (ready[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) pipe_open = drain();
    if (child_fd < 0 || (ready[1].revents & POLLIN) != 0) exited = child_exited();
  }
  if (exited && pipe_open && !outcome.too_long) (void)drain();  // what it wrote before its end
  if (child_fd >= 0) ::close(child_fd);
  ::close(pipe_ends[0]);
  // the whole group, whatever its state: a grandchild must not outlive the run
  // (pid is not reaped yet, so the group's id is still this child's)
  ::kill(-pid, SIGKILL);
  ::kill(pid, SIGKILL);
  while (::waitpid(pid, &outcome.wait_status, 0) < 0 && errno == EINTR) {
  }
  return outcome;
}

std::string child_failure_text(const ChildOutcome& outcome, double wall_limit_s, std::size_t max_answer_bytes) {
  if (outcome.timed_out)
    return "was still running after the wall-clock limit of " + seconds_text(wall_limit_s) +
           " s (--stepper-timeout) and was killed";
  if (outcome.too_long)
    return "crashed: its process sent more than " + std::to_string(max_answer_bytes) +
           " bytes (the limit of an answer) and was killed";
  if (WIFSIGNALED(outcome.wait_status))
    return "crashed: its process was killed by " + signal_text(WTERMSIG(outcome.wait_status));
  const int code = WIFEXITED(outcome.wait_status) ? WEXITSTATUS(outcome.wait_status) : -1;
  if (code == kExitCalledCode) return "crashed: it called exit() in its process";
  return "crashed: its process exited with code " + std::to_string(code) + " without returning a whole result";
}

RunResult run_isolated(const std::function<RunResult()>& body, const std::string& who, double wall_limit_s,
                       const FlatState& start, bool warm_up) {
  const ChildOutcome outcome =
      run_in_child([&] { return child_answer(body, warm_up); }, who, wall_limit_s, kMaxIsolatedAnswerBytes);

  RunResult run;
  run.final_state = start;
  auto lost = [&](Status status, const std::string& text) {
    run.status = status;
    run.message = who + " " + text + "; its state and cost are lost";
    return run;
  };
  const bool exited_clean = WIFEXITED(outcome.wait_status) && WEXITSTATUS(outcome.wait_status) == 0;
  if (outcome.timed_out)
    return lost(Status::timeout, child_failure_text(outcome, wall_limit_s, kMaxIsolatedAnswerBytes));
  if (outcome.too_long || !exited_clean)
    return lost(Status::crashed, child_failure_text(outcome, wall_limit_s, kMaxIsolatedAnswerBytes));
  Reader in(outcome.answer);
  std::uint32_t magic = 0, end_magic = 0;
  Kind kind{};
  bool whole = in.get(magic) && magic == kMagic && in.get(kind);
  RunResult got;
  std::string message, key;
  std::int32_t column = 0;
  if (whole) {
    switch (kind) {
      case Kind::result: whole = get_result(in, got); break;
      case Kind::input_error: whole = in.get_text(message) && in.get_text(key) && in.get(column); break;
      case Kind::exception: whole = in.get_text(message); break;
      default: whole = false;
    }
  }
  whole = whole && in.get(end_magic) && end_magic == kMagic && in.at_end();
  if (!whole) return lost(Status::crashed, "crashed: its process exited with code 0 without returning a whole result");
  if (kind == Kind::input_error) throw InputError(message, key, column);
  if (kind == Kind::exception) throw std::runtime_error(message);  // as it would have been in-process
  return got;
}

}  // namespace rb

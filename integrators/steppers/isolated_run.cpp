#include "integrators/steppers/isolated_run.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
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

[[noreturn]] void run_child(const std::function<RunResult()>& body, int out, bool warm_up) {
  // nothing but the answer's pipe stays open: a sibling child must not
  // hold another run's pipe (its parent would wait for that child's end)
  if (out > 3) ::close_range(3, static_cast<unsigned>(out) - 1, 0);
  ::close_range(static_cast<unsigned>(out) + 1, ~0U, 0);
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);  // a crash is a status, not a core file
  // the default action for the signals of a crash, whatever handler the
  // parent has (a sanitizer's turns SIGSEGV into exit code 1): the parent
  // names the signal
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS}) std::signal(signal, SIG_DFL);
  int code = 0;
  try {
    const std::string answer = child_answer(body, warm_up);
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

RunResult run_isolated(const std::function<RunResult()>& body, const std::string& who, double wall_limit_s,
                       const FlatState& start, bool warm_up) {
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
  if (pid == 0) run_child(body, pipe_ends[1], warm_up);
  ::close(pipe_ends[1]);

  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::duration<double>(wall_limit_s);
  std::string answer;
  bool timed_out = false;
  char buffer[1 << 16];
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - clock::now()).count();
    if (left <= 0.0) {
      timed_out = true;
      break;
    }
    pollfd ready{pipe_ends[0], POLLIN, 0};
    const int polled = ::poll(&ready, 1, static_cast<int>(std::min(left * 1000.0 + 1.0, double(INT_MAX))));
    if (polled <= 0) continue;  // EINTR or the time is up: the loop looks at the clock
    const ssize_t n = ::read(pipe_ends[0], buffer, sizeof buffer);
    if (n > 0) {
      answer.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;  // the child closed its end: it ended, one way or another
    }
  }
  ::close(pipe_ends[0]);
  if (timed_out) ::kill(pid, SIGKILL);  // not reaped yet: the pid is still the child's
  int wait_status = 0;
  while (::waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
  }

  RunResult run;
  run.final_state = start;
  if (timed_out) {
    run.status = Status::timeout;
    run.message = who + " was still running after the wall-clock limit of " + seconds_text(wall_limit_s) +
                  " s (--stepper-timeout) and was killed; its state and cost are lost";
    return run;
  }
  if (WIFSIGNALED(wait_status)) {
    run.status = Status::crashed;
    run.message = who + " crashed: its process was killed by " + signal_text(WTERMSIG(wait_status)) +
                  "; its state and cost are lost";
    return run;
  }
  Reader in(answer);
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
  const int code = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  if (!whole || code != 0) {
    run.status = Status::crashed;
    run.message = who + " crashed: its process exited with code " + std::to_string(code) +
                  " without returning a whole result; its state and cost are lost";
    return run;
  }
  if (kind == Kind::input_error) throw InputError(message, key, column);
  if (kind == Kind::exception) throw std::runtime_error(message);  // as it would have been in-process
  return got;
}

}  // namespace rb

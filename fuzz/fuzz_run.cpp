// libFuzzer target: a short run of a few integrators, one or more of each
// kind of driver, on a fuzzed scene. The scene's t_end is clamped and the
// step budget is small, so one input runs in milliseconds. With valid
// options, integrate() must not throw at all, and its result must keep the
// promises of integrator.hpp whatever the landscape does: a status with a
// reason, a stop time within the run, finite kept rows up to the stop.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"

namespace {

// the fixed-step loop of each family, an adaptive one of each library, and
// an implicit one (the AD Jacobian); missing names are skipped, so the
// registry may change under the fuzzer
constexpr const char* kMethods[] = {
    "rk4", "rkmk4", "odeint-rk4", "gsl-rkf45-adaptive", "gsl-rk4imp", "odeint-dopri5-adaptive", "rkmk-dp54-adaptive"};
constexpr double kMaxTime = 0.5;  // seconds of simulated time
constexpr long kMaxSteps = 60;    // accepted + rejected steps
constexpr double kTolerances[] = {1e-3, 1e-6, 1e-9, 1e-13, 1e-17};

[[noreturn]] void fail(const std::string& method, const char* what, const std::string& detail = {}) {
  std::fprintf(stderr, "fuzz_run: %s: %s %s\n", method.c_str(), what, detail.c_str());
  std::abort();
}

std::uint64_t hash_of(const std::uint8_t* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
  return h;
}

void check_run(const rb::Problem& problem, const rb::RunOptions& o, const std::string& name, const rb::RunResult& r) {
  const std::string_view status = rb::status_name(r.status);
  if (r.status != rb::Status::ok && r.message.empty()) fail(name, "stopped without a reason:", std::string(status));
  if (!(r.stop_time >= 0.0) || r.stop_time > o.t_end) fail(name, "stop_time outside [0, t_end]");
  if (!r.final_state.allFinite()) fail(name, "the final state is not finite; status", std::string(status));
  if (r.output.t.size() != r.output.y.size()) fail(name, "times and states differ in number");
  if (r.output.t.size() > o.output_times.size()) fail(name, "more rows than output times");
  double last = 0.0;
  for (std::size_t i = 0; i < r.output.t.size(); ++i) {
    if (!(r.output.t[i] > last) || r.output.t[i] > r.stop_time)
      fail(name, "a row's time is out of order or after the stop");
    if (r.output.t[i] != o.output_times[i]) fail(name, "a row is not at its output time");
    if (!r.output.y[i].allFinite()) fail(name, "a kept row is not finite");
    last = r.output.t[i];
  }
  if (r.status == rb::Status::ok &&
      (r.stop_time != o.t_end || r.output.t.size() != o.output_times.size() || r.final_state != r.output.y.back()))
    fail(name, "status ok but the run did not reach t_end with every row");
  if (r.cost.steps > o.max_steps) fail(name, "more accepted steps than max_steps");
  (void)problem;
}

}  // namespace

// a compiler run per new landscape would stall the fuzzer: the tape it is
// (fuzz_formula compares the native code with the tape)
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("RB_NATIVE_FORMULA", "off", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // a refused input is refused, wherever the refusal comes (fuzz_scene
  // checks the errors and that an accepted scene builds its problem)
  std::optional<rb::Problem> built;
  try {
    built.emplace(rb::make_problem(rb::parse_scene(text, "<fuzz>")));
  } catch (const rb::InputError&) {
    return 0;
  }
  const rb::Problem& problem = *built;
  // options from the input's hash: every input a different step and tolerance
  const std::uint64_t h = hash_of(data, size);
  rb::RunOptions o;
  o.t_end = std::min(problem.t_end(), kMaxTime);
  o.max_steps = kMaxSteps;
  for (int k = 1; k < 4; ++k) o.output_times.push_back(o.t_end * k / 4.0);
  o.output_times.push_back(o.t_end);
  const double step = o.t_end / static_cast<double>(1 + (h & 63));
  const double tol = kTolerances[(h >> 8) % std::size(kTolerances)];
  // the checks below hold for valid options only: a step > 0 and rising
  // output times. parse_scene keeps t_end >= kMinTEnd (a subnormal t_end
  // made the step 0, a fixed-step method threw and this harness aborted:
  // regress-subnormal-t-end.json; fuzz_scene checks the bounds); options
  // that are not valid all the same are skipped, not blamed on the methods
  if (!(step > 0.0) || !std::is_sorted(o.output_times.begin(), o.output_times.end(), std::less_equal<>()) ||
      !(o.output_times.front() > 0.0))
    return 0;
  for (const char* name : kMethods) {
    const rb::Integrator* m = nullptr;
    for (const auto& candidate : rb::registry())
      if (candidate->name() == name) m = candidate.get();
    if (!m) continue;
    rb::RunOptions mine = o;
    if (m->adaptive()) {
      mine.tolerances = rb::Tolerances(tol, tol);
      mine.h = (h >> 16) & 1 ? step : 0.0;  // a given first step, or the method's own
    } else {
      mine.h = step;
    }
    rb::RunResult r;
    try {
      r = m->integrate(problem, mine);
    } catch (const std::exception& e) {
      fail(name, "threw with valid options:", e.what());
    }
    check_run(problem, mine, name, r);
  }
  return 0;
}

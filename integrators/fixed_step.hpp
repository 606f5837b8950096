#pragma once
// The loop every fixed-step method shares: uniform steps of about h that land
// exactly on each output time, the per-step validity check, the full check at
// outputs, the step budget, and the bookkeeping of a run that stops early.
#include <cmath>

#include "integrators/integrator.hpp"
#include "problems/input_error.hpp"

namespace rb {

// The output times of a run: options.output_times with t_end appended when
// missing. Throws InputError when they are not increasing within (0, t_end].
std::vector<double> output_times_of(const Problem& problem, const RunOptions& options);

// The effective end time of a run.
inline double t_end_of(const Problem& problem, const RunOptions& options) {
  return options.t_end > 0.0 ? options.t_end : problem.t_end();
}

// Runs step(y, t, h, cost) repeatedly. step advances y in place from t to
// t + h and adds its own counts (rhs_evals, exp_evals, ...) to cost; the
// driver counts steps. Between two outputs t_a < t_b it takes
// n = ceil((t_b - t_a) / h) equal steps, so h is kept exactly when the output
// spacing is a multiple of h.
template <class StepFn>
RunResult drive_fixed_step(const Problem& problem, const RunOptions& options, StepFn&& step) {
  if (!(options.h > 0.0) || !std::isfinite(options.h))
    throw InputError("a fixed-step method needs a step h > 0", "h");
  const std::vector<double> outputs = output_times_of(problem, options);
  RunResult run;
  run.output.t.reserve(outputs.size());
  run.output.y.reserve(outputs.size());
  FlatState y = problem.y0();
  double t = 0.0;
  auto stop = [&](const Validity& v, const FlatState& last_valid, double t_valid) {
    run.status = v.status;
    run.message = v.reason;
    run.final_state = last_valid;
    run.stop_time = t_valid;
    return run;
  };
  for (const double t_out : outputs) {
    const double span = t_out - t;
    const double n_real = std::ceil(span / options.h * (1.0 - 1e-12));
    if (n_real > 1e15) return stop({Status::max_steps, "the step count overflows"}, y, t);
    const long n = std::max(1L, static_cast<long>(n_real));
    const double h = span / static_cast<double>(n);
    const double t_start = t;
    for (long i = 0; i < n; ++i) {
      if (run.cost.steps + run.cost.rejected >= options.max_steps)
        return stop({Status::max_steps, "reached max_steps = " + std::to_string(options.max_steps)}, y, t);
      FlatState next = y;
      step(next, t, h, run.cost);
      ++run.cost.steps;
      const Validity v = problem.check_step(next);
      if (v.status != Status::ok) return stop(v, y, t);
      y = next;
      t = (i + 1 == n) ? t_out : t_start + static_cast<double>(i + 1) * h;
    }
    const Validity v = problem.check_full(y);
    if (v.status != Status::ok) return stop(v, y, t);
    run.output.push(t, y);
  }
  run.final_state = y;
  run.stop_time = t;
  return run;
}

}  // namespace rb

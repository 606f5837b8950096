#pragma once
// The loop every adaptive method shares, in the spirit of drive_fixed_step:
// the step-size controller's steps, landing on each output time (clamped
// steps for controlled steppers, interpolation for dense output), the
// validity check of every accepted state, the step budget
// (accepted + rejected), step-size underflow, and turning a library's
// failures into statuses with the time of the last valid state.
//
// Any library's stepper fits (odeint's here, GSL's later) by offering:
//
//   static constexpr bool dense_output;
//   Attempt attempt(double t, double& h, Cost& cost);
//       tries one step of h from its current state at time t. accepted: its
//       state is now the one at t + h; rejected: its state is unchanged. Either
//       way h becomes the step its controller proposes next. It adds its own
//       counts (rhs_evals, ...) to cost; the driver counts steps and
//       rejections. A failure is thrown: StepFailure carries its status, any
//       other std::exception becomes Status::error with its message.
//   void state(FlatState& y) const;             the current state
//   void interpolate(double t, FlatState& y) const;
//       dense output only: the state at t within the last accepted step.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <string>

#include "integrators/fixed_step.hpp"

namespace rb {

// Tolerances of an adaptive run, as the error norm of the controller uses
// them: a component's error is measured against atol + rtol * |y_i|.
struct Tolerances {
  double rtol = 0.0;
  double atol = 0.0;
};

// The tolerances of options, checked: finite, >= 0, not both 0; also checks
// that the initial step options.h is finite and >= 0 (0 = automatic).
// Throws InputError naming the option.
Tolerances tolerances_of(const RunOptions& options);

// The smallest step time can resolve near t: a controller proposing less is
// a step-size underflow (at 1e-14 relative, a step barely changes t).
inline double min_step_at(double t) { return 1e-14 * std::max(1.0, std::abs(t)); }

// Whether a controller can meet tol at all: not when both tolerances are
// below the rounding of the state (rtol < 4 eps and atol < 4 eps max|y0_i|,
// eps = 2.2e-16). Error estimates then sit in rounding noise: a controller
// either creeps at tiny steps or accepts steps whose true error exceeds the
// tolerance and reports ok. drive_adaptive ends such a run at t = 0 with
// step_underflow (the step that tolerance needs is below what can be
// resolved). Status ok when attainable.
Validity attainable(const Tolerances& tol, const FlatState& y0);

// A first step for a method of the given order from y0 (Hairer, Norsett &
// Wanner, Solving ODEs I, II.4, as in DOPRI5's hinit): two rhs evaluations,
// counted in cost. At most span (the time to the end of the run).
double initial_step(const Problem& problem, const FlatState& y0, const Tolerances& tol, int order, double span,
                    Cost& cost);

// "the step size fell to 3.2e-15 at t = 0.25" (numbers in %g).
std::string underflow_message(double h, double t);

// What one attempt of an adaptive step did.
enum class Attempt { accepted, rejected };

// A failure a stepper raises from inside an attempt (a library's error code
// or exception) with the status the run should end with.
class StepFailure : public std::runtime_error {
 public:
  StepFailure(Status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  Status status() const { return status_; }

 private:
  Status status_;
};

// Runs stepper (see the top of this file) from the problem's start to the
// last output time. options.h > 0 is the first step tried; 0 asks
// initial_step for one. Never throws for a failing method; throws
// InputError for bad options.
template <class Stepper>
RunResult drive_adaptive(const Problem& problem, const RunOptions& options, int order, Stepper& stepper) {
  const Tolerances tol = tolerances_of(options);
  const std::vector<double> outputs = output_times_of(problem, options);
  const double t_end = outputs.back();
  RunResult run;
  run.output.t.reserve(outputs.size());
  run.output.y.reserve(outputs.size());
  FlatState y = problem.y0();
  double t = 0.0;
  // moved out, not copied: the rows may be many
  auto stop = [&](Status status, const std::string& reason, const FlatState& last_valid, double t_valid) {
    return std::move(run.stopped(status, reason, last_valid, t_valid));
  };
  if (const Validity v = attainable(tol, y); v.status != Status::ok) return stop(v.status, v.reason, y, t);
  // the start, checked as every accepted state is (see below)
  ++run.cost.validity_checks;
  if (const Validity v = problem.check_full(y); v.status != Status::ok)
    return stop(v.status, model_stop_reason(v, t), y, t);
  double h = options.h > 0.0 ? options.h : initial_step(problem, y, tol, order, t_end, run.cost);
  FlatState y_new, y_out;  // reused: no allocation in the loop
  std::size_t next = 0;  // the next output to record
  while (next < outputs.size()) {
    if (run.cost.steps + run.cost.rejected >= options.max_steps)
      return stop(Status::max_steps, "reached max_steps = " + std::to_string(options.max_steps), y, t);
    if (!(h >= min_step_at(t)))  // also catches a NaN step
      return stop(Status::step_underflow, underflow_message(h, t), y, t);
    // controlled steppers land on every output, dense ones on t_end only;
    // a remainder below min_step is taken in this step rather than alone
    const double bound = Stepper::dense_output ? t_end : outputs[next];
    const bool lands = t + h >= bound - min_step_at(bound);
    const double h_try = lands ? bound - t : h;
    double h_next = h_try;
    Attempt attempt;
    try {
      attempt = stepper.attempt(t, h_next, run.cost);
    } catch (const StepFailure& e) {
      return stop(e.status(), e.what(), y, t);
    } catch (const std::exception& e) {
      return stop(Status::error, e.what(), y, t);
    } catch (...) {
      return stop(Status::error, "unknown exception from the stepper", y, t);
    }
    if (attempt == Attempt::rejected) {
      ++run.cost.rejected;
      h = h_next;
      continue;
    }
    ++run.cost.steps;
    const double t_old = t;
    t = lands ? bound : t + h_try;
    // a step shortened to land says little about the next one: keep the
    // controller's previous proposal when it was larger
    h = lands ? std::max(h_next, h) : h_next;
    // a step to an invalid state ends the run at the last valid one; no
    // output is interpolated towards it. The model's limits are checked at
    // every accepted state by one evaluation there (a library's stepper
    // does not say where it evaluates), counted like drive_fixed_step's
    stepper.state(y_new);
    const Validity v = problem.check_step(y_new);
    if (v.status != Status::ok) return stop(v.status, v.reason, y, t_old);
    ++run.cost.validity_checks;
    if (const Validity m = problem.check_full(y_new); m.status != Status::ok)
      return stop(m.status, model_stop_reason(m, t), y, t_old);
    // record every output this step reached
    if constexpr (Stepper::dense_output) {
      for (; next < outputs.size() && outputs[next] <= t; ++next) {
        const double t_out = outputs[next];
        if (t_out == t)
          y_out = y_new;
        else
          stepper.interpolate(t_out, y_out);
        // a non-finite interpolant (the dense output can see what the
        // step's end did not) is not a state to end on
        const Validity at = problem.check_step(y_out);
        if (at.status != Status::ok) {
          const bool none = run.output.y.empty();
          return stop(at.status, at.reason, none ? y : run.output.y.back(), none ? t_old : run.output.t.back());
        }
        run.output.push(t_out, y_out);
      }
    } else if (lands) {
      run.output.push(t, y_new);
      ++next;
    }
    y = y_new;
  }
  run.final_state = y;
  run.stop_time = t;
  return run;
}

}  // namespace rb

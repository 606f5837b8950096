#pragma once
// What a run is made of besides stepping, shared by the driver's loops
// (integrators/driver.hpp, integrators/adaptive_loops.hpp): the output times, the step budget, the model's
// checks with their count, and the ways a run ends.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

// The output times of a run: options.output_times with t_end appended when
// missing. Throws InputError when they are not increasing within (0, t_end].
std::vector<double> output_times_of(const Problem& problem, const RunOptions& options);

// The effective end time of a run.
inline double t_end_of(const Problem& problem, const RunOptions& options) {
  return options.t_end > 0.0 ? options.t_end : problem.t_end();
}

// A model check's reason with the time it failed at (lift-off, curvature).
std::string model_stop_reason(const Validity& v, double t);
// Where in a step a limit was met: at one of its stages, or on its path
// between them (the driver's check_step_path).
enum class InStep { stage, path };
// The reason of a limit met within the step of h from t: "r * max curvature
// reached 1.04 at t = 0.3 (at a stage of the step of h = 0.05 from there)",
// or "(between the stages of the step ...)" on the path.
std::string step_stop_reason(const Validity& v, double t, double h, InStep where = InStep::stage);
// The model's limit that margins m are beyond: curvature or lift-off; ok
// otherwise (also for a false alarm). Non-finite margins (diverged) count
// only with non_finite: the fixed-step loop stops there; an adaptive one
// shrinks a non-finite trial by its own rule.
Validity model_limit(const Problem& problem, const ModelMargins& m, bool non_finite = false);

// A failure a stepper raises from inside a step (a library's error code or
// exception) with the status the run should end with. The driver ends the
// run at the last valid state; the step is not counted.
class StepFailure : public std::runtime_error {
 public:
  StepFailure(Status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  Status status() const { return status_; }

 private:
  Status status_;
};

// What every loop keeps of a run: its outputs, its result so far and the ways
// it ends.
class RunBook {
 public:
  RunBook(const Problem& problem, const RunOptions& options)
      : problem_(problem), outputs_(output_times_of(problem, options)), max_steps_(options.max_steps) {
    run_.output.t.reserve(outputs_.size());
    run_.output.y.reserve(outputs_.size());
  }

  const std::vector<double>& outputs() const { return outputs_; }
  Cost& cost() { return run_.cost; }
  Trajectory& output() { return run_.output; }

  bool over_budget() const { return run_.cost.steps + run_.cost.rejected >= max_steps_; }

  // Ends the run at last_valid (time t_valid); moved out, not copied: the
  // rows may be many.
  RunResult stop(Status why, const std::string& reason, const FlatState& last_valid, double t_valid) {
    return std::move(run_.stopped(why, reason, last_valid, t_valid));
  }
  // Ends the run at the state before the current one (the current one found
  // beyond the model's limits by v), without the rows recorded after it.
  RunResult stop_before(const Validity& v, const FlatState& y_before, double t_before) {
    while (!run_.output.t.empty() && run_.output.t.back() > t_before) {
      run_.output.t.pop_back();
      run_.output.y.pop_back();
    }
    return stop(v.status, v.reason, y_before, t_before);
  }
  RunResult stop_over_budget(const FlatState& y, double t) {
    return stop(Status::max_steps, "reached max_steps = " + std::to_string(max_steps_), y, t);
  }

  // The model's check of a state at time t by one evaluation there
  // (Problem::check_full), counted in Cost::validity_checks; the reason
  // carries t.
  Validity check_model_at(const FlatState& y, double t) {
    ++run_.cost.validity_checks;
    Validity v = problem_.check_full(y);
    if (v.status != Status::ok) v.reason = model_stop_reason(v, t);
    return v;
  }

  // The limit a stage of the last step went beyond (Cost::watch; see
  // model_limit), then clears the watch.
  Validity stage_limit(bool non_finite = false) {
    run_.cost.watch.beyond = false;
    return model_limit(problem_, run_.cost.watch.first, non_finite);
  }

  // The run reached its end at y, time t.
  RunResult finish(const FlatState& y, double t) {
    run_.final_state = y;
    run_.stop_time = t;
    return std::move(run_);
  }

 private:
  const Problem& problem_;
  std::vector<double> outputs_;
  long max_steps_;
  RunResult run_;
};

}  // namespace rb

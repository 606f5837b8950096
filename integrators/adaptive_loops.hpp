#pragma once
// The driver's adaptive loops (integrators/driver.hpp), one per stepper
// protocol, each a short loop over what they share (AdaptiveRun,
// integrators/adaptive_run.hpp): the outputs and landing on them (clamped
// steps, or interpolation for a stepper with a dense output), the step
// budget, the model's checks, the refusals and the stops.
//
// Every stepper offers
//
//   static constexpr bool dense_output;
//   void state(FlatState& y) const;             the current state
//   void interpolate(double t, FlatState& y) const;
//       dense output only: the state at t within the last accepted step;
//   void restore(const FlatState& y);           back to y, the current state,
//       after a step the driver refuses (see below);
//
// and one of three ways to step, each with its loop:
//
// - drive_estimating: an error estimate (the suite's pairs: RKMK, flat,
//   exponential products), and a controller composed with it, a value its
//   caller makes (FilterController: i, pi, pid):
//     int error_order() const;                  k, err = O(h^k)
//     double try_step(double t, double h, Cost& cost);
//         the error norm of a step of h from the current state (<= 1 meets
//         the tolerance; not finite where the step left where F is finite);
//         the state is unchanged;
//     void accept(double t, double h, Cost& cost);
//         makes the tried step the current state.
//   The controller decides; a non-finite error shrinks the step hard
//   (FilterController::shrink) and the run ends diverged after
//   kMaxNonFiniteTrials of them.
// - drive_own_controller: its own controller (odeint):
//     Attempt attempt(double t, double& h, Cost& cost);
//         tries one step of h. accepted: its state is now the one at t + h;
//         rejected: unchanged. Either way h becomes the step it proposes next.
// - drive_lands_itself: its own controller and its own landing (GSL's
//   evolve):
//     void advance(double& t, double bound, double& h, Cost& cost);
//         one accepted step from t towards bound (landing on it when near),
//         t and h updated, its own rejections added to cost.rejected;
//     double first_step(double span) const;     the first h when options.h = 0.
//
// Every stage a stepper evaluates goes through stage_flat_rhs /
// stage_lie_rhs (or Cost::note), rejected attempts' included: an attempt
// with a stage beyond the model's limits (curvature, lift-off) is rejected
// (a library's accepted step undone by restore) and retried at kLimitShrink
// of its step; the run stops at y with that limit's status only when the
// step can shrink no further (min_step_at), or at the state before y when y
// itself is beyond it (checked then, by one evaluation). Every accepted
// step that moved the contact point more than kPathSpacing radii (from its
// chord and its stages' contact speeds, StageWatch::speed2) has its path
// between its stages checked as well (check_step_path), whatever the output
// spacing; after the first such refusal, or once a stage came near the
// curvature limit (r max kappa >= 1/2), every step's path is, and a step
// that moves the contact point more than kNearLimitTravel radii is undone
// and retried shorter. A step whose path goes beyond a limit is undone and
// refused the same way. The start and the end get one evaluation each; all
// are counted in Cost::validity_checks (docs/design.md, "Validity along
// every step").
// A stepper adds its own counts (rhs_evals, ...) to cost; the driver counts
// steps and rejections. A failure is thrown: StepFailure carries its status,
// any other std::exception becomes Status::error with its message.
// options.h > 0 is the first step tried; 0 asks initial_step for one (the
// lands-itself stepper's first_step). Never throws for a failing method;
// throws InputError for bad options.
#include <cmath>

#include "integrators/adaptive_run.hpp"
#include "integrators/controllers/controller.hpp"

namespace rb {

// A stepper with an error estimate, for a method of the given order (its
// first step), its steps decided by controller.
template <class Stepper>
RunResult drive_estimating(const Problem& problem, const RunOptions& options, int order, Stepper& stepper,
                           FilterController controller) {
  AdaptiveRun run(problem, options);
  run.start([&] { return run.automatic_step(order); });
  int nonfinite_trials = 0;
  while (run.step_ahead(Stepper::dense_output)) {
    const double t = run.t(), h_try = run.h_try();
    bool accepted = false;
    double h_next = h_try;
    auto try_one = [&] {
      const double err = stepper.try_step(t, h_try, run.cost());
      if (run.beyond_limit()) [[unlikely]]
        return;
      if (!std::isfinite(err)) {
        // a trial step that left where F is finite (past a landscape's
        // edge) was too large: shrink it hard. If the state itself blows
        // up (or the edge is met again and again), the run ends diverged.
        if (++nonfinite_trials > kMaxNonFiniteTrials) throw nonfinite_failure(t, nonfinite_trials, h_try);
        h_next = controller.shrink(h_try);
        return;
      }
      const StepDecision d = controller.decide(err, h_try);
      accepted = d.accepted;
      h_next = d.h_next;
      if (accepted) stepper.accept(t, h_try, run.cost());
    };
    if (!run.attempt(try_one, [] {})) break;
    run.settle(stepper, accepted, h_next);
  }
  return run.result();
}

// A stepper with its own controller, for a method of the given order (its
// first step).
template <class Stepper>
RunResult drive_own_controller(const Problem& problem, const RunOptions& options, int order, Stepper& stepper) {
  AdaptiveRun run(problem, options);
  run.start([&] { return run.automatic_step(order); });
  auto back_to_y = [&] { stepper.restore(run.y()); };
  while (run.step_ahead(Stepper::dense_output)) {
    bool accepted = false;
    double h_next = run.h_try();
    auto try_one = [&] {
      accepted = stepper.attempt(run.t(), h_next, run.cost()) == Attempt::accepted;
      // a stage beyond a limit undoes what the library accepted
      if (run.beyond_limit() && accepted) back_to_y();
    };
    if (!run.attempt(try_one, back_to_y)) break;
    run.settle(stepper, accepted, h_next);
  }
  return run.result();
}

// A stepper with its own controller that lands on the outputs itself.
template <class Stepper>
RunResult drive_lands_itself(const Problem& problem, const RunOptions& options, Stepper& stepper) {
  AdaptiveRun run(problem, options);
  run.start([&] { return stepper.first_step(run.t_end()); });
  auto back_to_y = [&] { stepper.restore(run.y()); };
  while (run.step_ahead(Stepper::dense_output)) {
    double t_new = run.t(), h_next = run.h();
    auto try_one = [&] {
      stepper.advance(t_new, run.bound(), h_next, run.cost());
      // a stage beyond a limit undoes the library's step
      if (run.beyond_limit()) back_to_y();
    };
    if (!run.attempt(try_one, back_to_y)) break;
    run.settle_landed(stepper, t_new, h_next);
  }
  return run.result();
}

}  // namespace rb

#pragma once
// The one driver: every integrator's run goes through it. It owns what a run
// is made of besides the stepping: the output times and landing on them, the
// step budget (accepted + rejected steps), the model's validity checks of
// every evaluation a step makes (the margins each right-hand side computes;
// Cost::validity_checks counts the evaluations checked), the stop at the
// last valid state with a status and a reason, and turning a
// stepper's failure into that status. The stepper only steps; the step size
// comes from a controller (integrators/controllers/controller.hpp).
//
// Its loops share that bookkeeping (RunBook, integrators/run_book.hpp):
// - drive_fixed_step (here): the "constant" controller, uniform steps of
//   about h that land exactly on each output time. Its stepper is a functor
//   (see there), the shape every fixed-step stepper has.
// - the adaptive loops (integrators/adaptive_loops.hpp), one per stepper
//   protocol: drive_estimating (an error estimate and a FilterController),
//   drive_own_controller (odeint), drive_lands_itself (GSL's evolve). They
//   share an AdaptiveRun (integrators/adaptive_run.hpp); the helpers below
//   are theirs.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "integrators/controllers/controller.hpp"
#include "integrators/run_book.hpp"
#include "problems/input_error.hpp"

namespace rb {

// Runs step(y, t, h, cost) repeatedly with the "constant" controller. step
// advances y in place from t to t + h and adds its own counts (rhs_evals,
// exp_evals, ...) to cost; the driver counts steps. A step may instead take
// (y, next, t, h, cost) and write the state at t + h into next, leaving y as
// it is: that saves copying the state twice a step on the critical path of a
// cheap step. Every right-hand side the step evaluates goes through
// stage_flat_rhs / stage_lie_rhs (or Cost::note), so that its validity
// margins are tested at every stage (docs/design.md): a stage beyond a limit
// (curvature, lift-off) stops the run with that status at y, the last valid
// state, whose output row stays; if y itself is beyond it (checked then, by
// one evaluation) the run ends at the state before y without y's row. The
// start and the end (whose state no step's stages evaluate) are checked by
// one evaluation each. The loop keeps the state before the current one (where a run ends
// whose current state is found beyond a limit), the current one and the
// next, rotated after each accepted step. All of these checks are
// counted in Cost::validity_checks. A step that fails throws StepFailure.
// Between two outputs t_a < t_b it takes n = ceil((t_b - t_a) / h) equal
// steps, so h is kept exactly when the output spacing is a multiple of h;
// a slack of 1e-6 steps absorbs the rounding of the span on long runs with
// dense output (t ~ 10, span ~ 1e-5 has a relative error ~ 1e-10), which
// would add a step to an interval that h divides (the cost: steps at most
// 1e-6 longer than h). A non-finite state (also one only in R, which no
// right-hand side of the homogeneous ball reads) stops the run at the step
// where it appears.
template <class StepFn>
RunResult drive_fixed_step(const Problem& problem, const RunOptions& options, StepFn&& step) {
  constexpr bool writes_next = std::is_invocable_v<StepFn&, const FlatState&, FlatState&, double, double, Cost&>;
  const double h_given = options.h.fixed_step();
  RunBook book(problem, options);
  Cost& cost = book.cost();
  std::array<FlatState, 3> states = {problem.y0(), problem.y0(), FlatState()};  // rotated each step
  FlatState *before = &states[0], *y = &states[1], *next = &states[2];
  double t_before = 0.0, t = 0.0, h_step = h_given;  // h_step: the step being taken
  // a stage of the step of h from y beyond a limit: the run stops at y, or before it (y beyond it too)
  auto stop_at_limit = [&](const Validity& limit, double h) {
    if (const Validity at = book.check_model_at(*y, t); at.status != Status::ok)
      return book.stop_before(at, *before, t_before);
    return book.stop(limit.status, step_stop_reason(limit, t, h), *y, t);
  };
  if (const Validity v = book.check_model_at(*y, t); v.status != Status::ok)
    return book.stop_before(v, *before, t_before);
  try {
    for (const double t_out : book.outputs()) {
      const double span = t_out - t;
      const double n_real = std::ceil(span / h_given - 1e-6);  // the slack: see above
      if (n_real > 1e15) return book.stop(Status::max_steps, "the step count overflows", *y, t);
      const long n = std::max(1L, static_cast<long>(n_real));
      const double h = span / static_cast<double>(n);
      h_step = h;
      const double t_start = t;
      for (long i = 0; i < n; ++i) {
        if (book.over_budget()) return book.stop_over_budget(*y, t);
        if constexpr (writes_next) {
          step(std::as_const(*y), *next, t, h, cost);
        } else {
          *next = *y;
          step(*next, t, h, cost);
        }
        if (cost.watch.beyond) [[unlikely]]
          if (const Validity v = book.stage_limit(true); v.status != Status::ok) return stop_at_limit(v, h);
        ++cost.steps;
        if (!problem.surely_within_step(*next)) [[unlikely]]  // a NaN stops the run where it appears
          if (const Validity v = problem.check_step(*next); v.status != Status::ok)
            return book.stop(v.status, v.reason, *y, t);
        FlatState* const freed = before;
        before = y;
        y = next;
        next = freed;
        t_before = t;
        t = (i + 1 == n) ? t_out : t_start + static_cast<double>(i + 1) * h;
      }
      book.output().push(t, *y);
    }
  } catch (const StepFailure& e) {
    if (cost.watch.beyond)  // a failure where a stage went beyond a limit (an implicit solve there)
      if (const Validity v = book.stage_limit(true); v.status != Status::ok) return stop_at_limit(v, h_step);
    return book.stop(e.status(), e.what(), *y, t);
  }
  if (const Validity v = book.check_model_at(*y, t); v.status != Status::ok)  // no step starts from y
    return book.stop_before(v, *before, t_before);
  return book.finish(*y, t);
}

// ---- adaptive ----

// The tolerances of an adaptive run, options.tolerances (Tolerances,
// integrators/tolerances.hpp: checked where they entered), which it needs
// given (InputError "rtol" otherwise). The initial step options.h was
// checked where it entered (StepSize, integrators/step_size.hpp).
const Tolerances& tolerances_of(const RunOptions& options);

// The smallest step time can resolve near t: a controller proposing less is
// a step-size underflow (at 1e-14 relative, a step barely changes t).
inline double min_step_at(double t) { return 1e-14 * std::max(1.0, std::abs(t)); }

// Whether a controller can meet tol at all: not when both tolerances are
// below the rounding of the state (rtol < 4 eps and atol < 4 eps max|y0_i|,
// eps = 2.2e-16). Error estimates then sit in rounding noise: a controller
// either creeps at tiny steps or accepts steps whose true error exceeds the
// tolerance and reports ok. The adaptive loops end such a run at t = 0 with
// step_underflow. Status ok when attainable.
Validity attainable(const Tolerances& tol, const FlatState& y0);

// A first step for a method of the given order from y0 (Hairer, Norsett &
// Wanner, Solving ODEs I, II.4, as in DOPRI5's hinit): two rhs evaluations,
// counted in cost. At most span (the time to the end of the run).
double initial_step(const Problem& problem, const FlatState& y0, const Tolerances& tol, int order, double span,
                    Cost& cost);

// "the step size fell to 3.2e-15 at t = 0.25" (numbers in %g).
std::string underflow_message(double h, double t);

// The model's limits (curvature, lift-off) along the path of an accepted
// step of h from y0 to y1, between its stages: a step whose stages all miss
// a narrow region beyond a limit would otherwise cross it unseen
// (docs/design.md, "Validity along every step"). The path is the cubic
// Hermite interpolant of the flat state through y0, F(y0), y1, F(y1) (exact
// to O(h^4), whatever the stepper). Checked: its ends, then points on it
// whose contact points are at most kPathSpacing ball radii apart
// (consecutive ones, straight-line distance; at least min_points between
// the ends), and around a point near a limit (near_limit_at) the stretches
// to its neighbours again, at points at most kPathFineSpacing radii apart.
// The number of points between the ends starts from the contact travel (from
// the chord and the largest of the ends' and the stages' contact speeds,
// stage_speed), capped at kPathPointsMax. start: F(y0) when a check before
// evaluated it (the end of the step before), else evaluated here. Every
// evaluation is counted in cost.validity_checks. limit: the first limit
// met, ok otherwise (also where the margins are not finite: a non-finite
// path is the step's end check's to find); travel: the contact point's path
// length over the step from its chord and its end speeds (the near-limit
// rule, kNearLimitTravel); end: F(y1), for the next step.
inline constexpr double kPathSpacing = 1.0 / 8;
inline constexpr double kPathFineSpacing = 1.0 / 32;
inline constexpr int kPathPointsMin = 3;  // between the ends, near a limit
inline constexpr int kPathPointsMax = 4096;
// F at a state the path check evaluated, and whether it is near a limit.
struct PathSlope {
  FlatState f;
  bool near = false;
  bool known = false;
};
struct PathCheck {
  Validity limit;
  double travel = 0.0;
  PathSlope end;
};
PathCheck check_step_path(const Problem& problem, const FlatState& y0, const FlatState& y1, double h, Cost& cost,
                          const PathSlope& start = {}, double stage_speed = 0.0, int min_points = 0);
// Whether margins m were taken near one of the model's limits, where the
// path check looks closer: the landscape sharply curved (r times a
// principal curvature of either sign at least 1/2 in size: from the fit
// M = I - r II, I -+ 2 r II not positive definite; the concave half is
// ModelMargins::near_curvature_limit) or the normal force at most half the
// weight's share along the normal (m g0 N_z / 2). Non-finite margins are
// not near.
bool near_limit_at(const Problem& problem, const ModelMargins& m);
// Whether a step of h that moved the contact point by sqrt(chord2), its
// stages' contact speeds at most sqrt(stage_speed2), moved it at most
// kPathSpacing radii (squares: no root a step): such a step is covered by
// its stages and its ends (the stages of the step from each) and needs no
// path check far from the limits. False for NaN.
inline bool short_step(double chord2, double h, double stage_speed2, double radius) {
  const double reach2 = kPathSpacing * radius * kPathSpacing * radius;
  return (chord2 <= reach2) & (h * h * stage_speed2 <= reach2);
}

// Near the curvature limit a step may move the contact point at most this
// many ball radii: a longer one cannot resolve the landscape at the scale
// where the model stops holding, and its path (accurate or not) may pass a
// region beyond the limit that the exact path crosses. Such a step is
// refused and retried at the length that moves the contact point half as
// far.
inline constexpr double kNearLimitTravel = 0.5;

// The name of the controller a run of an adaptive method uses (the
// report's): the method's own (MethodInfo::controller) unless
// options.controller is a filter and the method's is one too; a library's
// controller and the constant one stay.
std::string controller_of(const std::string& method_default, const RunOptions& options);

// What one attempt of an adaptive step did (a stepper with its own controller).
enum class Attempt { accepted, rejected };

// Non-finite trial steps a run tolerates before it is called diverged.
inline constexpr int kMaxNonFiniteTrials = 10;
// The failure (Status::diverged) of a run whose trial steps from t were not
// finite trials times, the last of h.
StepFailure nonfinite_failure(double t, int trials, double h);

// How a step with a stage beyond the model's limits shrinks before it is
// tried again (hard, as after a non-finite trial).
inline constexpr double kLimitShrink = 0.25;

}  // namespace rb

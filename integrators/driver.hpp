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
// Two loops share that bookkeeping (RunBook, integrators/run_book.hpp):
// - drive_fixed_step: the "constant" controller, uniform steps of about h
//   that land exactly on each output time. Its stepper is a functor (see
//   there), the shape every fixed-step stepper has.
// - drive_adaptive: a controller's steps, landing on each output (clamped
//   steps, or interpolation for a stepper with a dense output).
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
// start and the end are checked by one evaluation each. All of these are
// counted in Cost::validity_checks. A step that fails throws StepFailure.
// Between two outputs t_a < t_b it takes n = ceil((t_b - t_a) / h) equal
// steps, so h is kept exactly when the output spacing is a multiple of h.
template <class StepFn>
RunResult drive_fixed_step(const Problem& problem, const RunOptions& options, StepFn&& step) {
  constexpr bool writes_next = std::is_invocable_v<StepFn&, const FlatState&, FlatState&, double, double, Cost&>;
  if (!(options.h > 0.0) || !std::isfinite(options.h)) throw InputError("a fixed-step method needs a step h > 0", "h");
  RunBook book(problem, options);
  Cost& cost = book.cost();
  // the state before the current one, the current one and the next,
  // rotated after each accepted step (the one before is where a run whose
  // current state is found beyond a limit ends)
  std::array<FlatState, 3> states = {problem.y0(), problem.y0(), FlatState()};
  FlatState* before = &states[0];
  FlatState* y = &states[1];
  FlatState* next = &states[2];
  double t_before = 0.0, t = 0.0;
  // the current state failed the model's check: end at the one before,
  // without the current state's output row
  auto stop_model = [&](const Validity& v) {
    Trajectory& out = book.output();
    if (!out.t.empty() && out.t.back() == t && t > t_before) {
      out.t.pop_back();
      out.y.pop_back();
    }
    return book.stop(v.status, v.reason, *before, t_before);
  };
  if (const Validity v = book.check_model_at(*y, t); v.status != Status::ok) return stop_model(v);
  double h_step = options.h;  // the step being taken
  try {
    for (const double t_out : book.outputs()) {
      const double span = t_out - t;
      // the slack absorbs the rounding of span on long runs with dense output
      // (t ~ 10, span ~ 1e-5 has a relative error ~ 1e-10), which would add
      // a step to an interval that h divides; the cost is steps at most 1e-6
      // longer than h
      const double n_real = std::ceil(span / options.h - 1e-6);
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
        if (cost.watch.beyond) [[unlikely]] {
          if (const Validity v = book.stage_limit(true); v.status != Status::ok) {
            if (const Validity at = book.check_model_at(*y, t); at.status != Status::ok) return stop_model(at);
            return book.stop(v.status, step_stop_reason(v, t, h), *y, t);
          }
        }
        ++cost.steps;
        // a NaN stops the run at the step where it appears (also one only in
        // R, which no right-hand side of the homogeneous ball reads)
        if (!problem.surely_within_step(*next)) [[unlikely]] {
          const Validity v = problem.check_step(*next);
          if (v.status != Status::ok) return book.stop(v.status, v.reason, *y, t);
        }
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
    // a step that failed where a stage went beyond a limit (an implicit
    // solve iterating there) stops with the limit
    if (cost.watch.beyond)
      if (const Validity v = book.stage_limit(true); v.status != Status::ok) {
        if (const Validity at = book.check_model_at(*y, t); at.status != Status::ok) return stop_model(at);
        return book.stop(v.status, step_stop_reason(v, t, h_step), *y, t);
      }
    return book.stop(e.status(), e.what(), *y, t);
  }
  // the last state: no step starts from it, so one evaluation of its own
  if (const Validity v = book.check_model_at(*y, t); v.status != Status::ok) return stop_model(v);
  return book.finish(*y, t);
}

// ---- adaptive ----

// The tolerances of an adaptive run, options.tolerances (Tolerances,
// integrators/tolerances.hpp: checked where they entered), which it needs
// given (InputError "rtol" otherwise); also that the initial step options.h
// is finite and >= 0 (0 = automatic; InputError "h").
const Tolerances& tolerances_of(const RunOptions& options);

// The smallest step time can resolve near t: a controller proposing less is
// a step-size underflow (at 1e-14 relative, a step barely changes t).
inline double min_step_at(double t) { return 1e-14 * std::max(1.0, std::abs(t)); }

// Whether a controller can meet tol at all: not when both tolerances are
// below the rounding of the state (rtol < 4 eps and atol < 4 eps max|y0_i|,
// eps = 2.2e-16). Error estimates then sit in rounding noise: a controller
// either creeps at tiny steps or accepts steps whose true error exceeds the
// tolerance and reports ok. drive_adaptive ends such a run at t = 0 with
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
// a narrow region beyond a limit would otherwise cross it unseen. The path
// is the cubic Hermite interpolant of the flat state through y0, F(y0), y1,
// F(y1) (exact to O(h^4), whatever the stepper), checked at interior points
// spaced so that the contact point moves at most a quarter of the ball's
// radius between two (at least kPathPointsMin, at most kPathPointsMax).
// Every evaluation is counted in cost.validity_checks. limit: the first
// limit met, ok otherwise (also where the margins are not finite: a
// non-finite path is the step's end check's to find); travel: the contact
// point's path length over the step (from its chord and its end speeds).
inline constexpr int kPathPointsMin = 3;
inline constexpr int kPathPointsMax = 64;
struct PathCheck {
  Validity limit;
  double travel = 0.0;
};
PathCheck check_step_path(const Problem& problem, const FlatState& y0, const FlatState& y1, double h, Cost& cost);

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

// How a step with a stage beyond the model's limits shrinks before it is
// tried again (hard, as after a non-finite trial).
inline constexpr double kLimitShrink = 0.25;

// Runs stepper from the problem's start to the last output time. A stepper
// offers
//
//   static constexpr bool dense_output;
//   void state(FlatState& y) const;             the current state
//   void interpolate(double t, FlatState& y) const;
//       dense output only: the state at t within the last accepted step;
//
// and one of three ways to step:
//
// - an error estimate, for the suite's controllers (the RKMK pairs):
//     int error_order() const;                  k, err = O(h^k)
//     double try_step(double t, double h, Cost& cost);
//         the error norm of a step of h from the current state (<= 1 meets
//         the tolerance; not finite where the step left where F is finite);
//         the state is unchanged;
//     void accept(double t, double h, Cost& cost);
//         makes the tried step the current state.
//   The controller (filter: the run's or the method's) decides; the driver
//   counts non-finite trials and ends the run diverged after
//   kMaxNonFiniteTrials.
// - its own controller (odeint):
//     Attempt attempt(double t, double& h, Cost& cost);
//         tries one step of h. accepted: its state is now the one at t + h;
//         rejected: unchanged. Either way h becomes the step it proposes next.
// - its own controller and its own landing (GSL's evolve), with
//   static constexpr bool lands_itself = true:
//     void advance(double& t, double bound, double& h, Cost& cost);
//         one accepted step from t towards bound (landing on it when near),
//         t and h updated, its own rejections added to cost.rejected;
//     double first_step(double span) const;     the first h when options.h = 0.
//
// Every stepper also offers
//     void restore(const FlatState& y);          back to y, the current state,
//         after a step the driver refuses (see below).
//
// Every stage a stepper evaluates goes through stage_flat_rhs /
// stage_lie_rhs (or Cost::note), rejected attempts' included: an attempt
// with a stage beyond the model's limits (curvature, lift-off) is rejected
// and retried at kLimitShrink of its step; the run stops at y with that
// limit's status only when the step can shrink no further (min_step_at),
// or at the state before y when y itself is beyond it (checked then, by
// one evaluation). After the first such refusal, or once a stage came near
// the curvature limit (r max kappa >= 1/2), every accepted step's path
// between its stages is checked as well (check_step_path): a step whose
// path goes beyond a limit is undone and refused the same way, and one that
// moves the contact point more than kNearLimitTravel radii is undone and
// retried shorter. The start
// and the end get one evaluation each; all are counted in
// Cost::validity_checks (docs/design.md).
// A stepper adds its own counts (rhs_evals, ...) to cost; the driver counts
// steps and rejections. A failure is thrown: StepFailure carries its status,
// any other std::exception becomes Status::error with its message.
// options.h > 0 is the first step tried; 0 asks initial_step for one. Never
// throws for a failing method; throws InputError for bad options.
template <class Stepper>
RunResult drive_adaptive(const Problem& problem, const RunOptions& options, int order, Stepper& stepper,
                         const ControllerKind* filter = nullptr) {
  constexpr bool estimates = requires(Stepper & s, Cost & c) { s.try_step(0.0, 0.0, c); };
  constexpr bool lands_itself = requires { requires Stepper::lands_itself; };
  const Tolerances tol = tolerances_of(options);
  RunBook book(problem, options);
  const std::vector<double>& outputs = book.outputs();
  const double t_end = outputs.back();
  Cost& cost = book.cost();
  FlatState y = problem.y0();
  double t = 0.0;
  // the accepted state before y, where a run ends whose y is found beyond a
  // limit; and whether y is known to be within them
  FlatState y_before = y;
  double t_before = 0.0;
  bool y_checked = true;
  auto stop_before = [&](const Validity& v) {
    Trajectory& out = book.output();
    while (!out.t.empty() && out.t.back() > t_before) {
      out.t.pop_back();
      out.y.pop_back();
    }
    return book.stop(v.status, v.reason, y_before, t_before);
  };
  if (const Validity v = attainable(tol, y); v.status != Status::ok) return book.stop(v.status, v.reason, y, t);
  // the start, by one evaluation (the steps' stages check every other state)
  if (const Validity v = book.check_model_at(y, t); v.status != Status::ok) return book.stop(v.status, v.reason, y, t);
  double h = 0.0;
  if (options.h > 0.0) h = options.h;
  else if constexpr (lands_itself) h = stepper.first_step(t_end);
  else h = initial_step(problem, y, tol, order, t_end, cost);
  auto make_controller = [&] {
    if constexpr (estimates) return FilterController(*filter, stepper.error_order());
    else return FilterController(filter_controllers().front(), 1);  // unused
  };
  [[maybe_unused]] FilterController controller = make_controller();
  // A step (of h_tried from y) refused for a stage beyond a limit
  // (curvature, lift-off): if y itself is beyond it, the run ends at the
  // state before; else the step shrinks, and the run stops at y only when
  // the limit is still met at the smallest step time resolves.
  // From the first such refusal on, and from the first stage near the
  // curvature limit (StageWatch::near), every accepted step's path between
  // its stages is checked too (check_step_path): the run is where a limit
  // is, and a step could jump the region its stages missed.
  bool check_paths = false;
  auto refuse = [&](const Validity& limit, double h_tried, InStep where = InStep::stage) -> std::optional<RunResult> {
    check_paths = true;
    if (!y_checked) {
      if (const Validity at = book.check_model_at(y, t); at.status != Status::ok) return stop_before(at);
      y_checked = true;
    }
    ++cost.rejected;
    if (!(h_tried > min_step_at(t))) return book.stop(limit.status, step_stop_reason(limit, t, h_tried, where), y, t);
    h = std::max(kLimitShrink * h_tried, min_step_at(t));
    return std::nullopt;
  };
  int nonfinite_trials = 0;
  FlatState y_new, y_out;  // reused: no allocation in the loop
  std::size_t next = 0;    // the next output to record
  while (next < outputs.size()) {
    if (book.over_budget()) return book.stop_over_budget(y, t);
    if (!(h >= min_step_at(t)))  // also catches a NaN step
      return book.stop(Status::step_underflow, underflow_message(h, t), y, t);
    // controlled steppers land on every output, dense ones on t_end only;
    // a remainder below min_step is taken in this step rather than alone
    const double bound = Stepper::dense_output ? t_end : outputs[next];
    bool lands = t + h >= bound - min_step_at(bound);
    const double h_try = lands ? bound - t : h;
    double h_next = h_try;
    double t_new = t + h_try;
    bool accepted = true;
    Validity limit;  // a stage of this attempt beyond the model's limits
    // a failure of an attempt (an implicit solve, a library's error) whose
    // stages went beyond a limit is that limit's rejection; the stepper
    // goes back to y
    auto failed_at_limit = [&] {
      if (!cost.watch.beyond) return false;
      limit = book.stage_limit();
      if (limit.status == Status::ok) return false;
      if constexpr (!estimates) stepper.restore(y);
      return true;
    };
    try {
      if constexpr (lands_itself) {
        t_new = t;
        h_next = h;
        stepper.advance(t_new, bound, h_next, cost);
        lands = t_new >= bound;
      } else if constexpr (estimates) {
        const double err = stepper.try_step(t, h_try, cost);
        if (cost.watch.beyond) limit = book.stage_limit();
        if (limit.status != Status::ok) [[unlikely]] {
          accepted = false;  // below
        } else if (!std::isfinite(err)) {
          // a trial step that left where F is finite (past a landscape's
          // edge) was too large: shrink it hard. If the state itself blows
          // up (or the edge is met again and again), the run ends diverged.
          if (++nonfinite_trials > kMaxNonFiniteTrials) {
            char text[160];
            std::snprintf(text, sizeof text,
                          "the state is not finite beyond t = %.9g (%d trial steps past it, the last of %.3g)", t,
                          nonfinite_trials, h_try);
            throw StepFailure(Status::diverged, text);
          }
          accepted = false;
          h_next = controller.shrink(h_try);
        } else {
          const StepDecision d = controller.decide(err, h_try);
          accepted = d.accepted;
          h_next = d.h_next;
          if (accepted) stepper.accept(t, h_try, cost);
        }
      } else {
        accepted = stepper.attempt(t, h_next, cost) == Attempt::accepted;
      }
      if constexpr (!estimates) {
        // a library's step: a stage beyond a limit undoes what it accepted
        if (cost.watch.beyond) [[unlikely]] {
          limit = book.stage_limit();
          if (limit.status != Status::ok && accepted) stepper.restore(y);
        }
      }
    } catch (const StepFailure& e) {
      if (!failed_at_limit()) return book.stop(e.status(), e.what(), y, t);
    } catch (const std::exception& e) {
      if (!failed_at_limit()) return book.stop(Status::error, e.what(), y, t);
    } catch (...) {
      return book.stop(Status::error, "unknown exception from the stepper", y, t);
    }
    if (limit.status != Status::ok) [[unlikely]] {
      if (std::optional<RunResult> stop = refuse(limit, lands_itself && t_new > t ? t_new - t : h_try)) return *stop;
      continue;
    }
    if (!accepted) {
      ++cost.rejected;
      h = h_next;
      continue;
    }
    ++cost.steps;
    const double t_old = t;
    // undoes the step just taken (refused after the fact); its length
    auto undo_step = [&] {
      stepper.restore(y);
      --cost.steps;
      const double h_tried = t - t_old;
      t = t_old;
      return h_tried;
    };
    if constexpr (lands_itself) {
      t = t_new;
      h = h_next;
    } else {
      t = lands ? bound : t_new;
      // a step shortened to land says little about the next one: keep the
      // controller's previous proposal when it was larger
      h = lands ? std::max(h_next, h) : h_next;
    }
    // a step to a non-finite state or out of the domain ends the run at the
    // last valid one; no output is interpolated towards it. The model's
    // limits were tested at every stage of the step.
    stepper.state(y_new);
    if (const Validity v = problem.check_step(y_new); v.status != Status::ok)
      return book.stop(v.status, v.reason, y, t_old);
    if (check_paths || cost.watch.near) [[unlikely]] {
      // a path beyond a limit between the stages, or a step too long to
      // resolve the landscape near one: the step is undone, refused
      const PathCheck path = check_step_path(problem, y, y_new, t - t_old, cost);
      const double reach = kNearLimitTravel * problem.model().params().radius;
      if (path.limit.status != Status::ok || path.travel > reach) {
        const double h_tried = undo_step();
        if (path.limit.status != Status::ok) {
          if (std::optional<RunResult> stop = refuse(path.limit, h_tried, InStep::path)) return *stop;
        } else {
          ++cost.rejected;
          h = h_tried * 0.5 * reach / path.travel;
        }
        continue;
      }
    }
    // record every output this step reached
    if constexpr (Stepper::dense_output) {
      Trajectory& out = book.output();
      const std::size_t rows_before = out.t.size(), next_before = next;
      Validity row_limit;
      for (; next < outputs.size() && outputs[next] <= t; ++next) {
        const double t_out = outputs[next];
        if (t_out == t) {
          y_out = y_new;
        } else {
          stepper.interpolate(t_out, y_out);
        }
        // a non-finite interpolant (the dense output can see what the
        // step's end did not) is not a state to end on
        const Validity at = problem.check_step(y_out);
        if (at.status != Status::ok) {
          const bool none = out.y.empty();
          return book.stop(at.status, at.reason, none ? y : out.y.back(), none ? t_old : out.t.back());
        }
        if (t_out != t) {
          // a row between the step's stages is a state the run reports:
          // checked as a stage is, by one evaluation (counted)
          cost.note(problem.model().margins_at(y_out));
          if (cost.watch.beyond && (row_limit = book.stage_limit()).status != Status::ok) break;
        }
        out.push(t_out, y_out);
      }
      if (row_limit.status != Status::ok) [[unlikely]] {
        // the step went beyond a limit between its stages: undone, refused
        out.t.resize(rows_before);
        out.y.resize(rows_before);
        next = next_before;
        if (std::optional<RunResult> stop = refuse(row_limit, undo_step())) return *stop;
        continue;
      }
    } else if (lands) {
      book.output().push(t, y_new);
      ++next;
    }
    y_before = y;
    t_before = t_old;
    y = y_new;
    y_checked = false;
  }
  // the last state: no step starts from it, so one evaluation of its own
  if (const Validity v = book.check_model_at(y, t); v.status != Status::ok) return stop_before(v);
  return book.finish(y, t);
}

}  // namespace rb

#pragma once
// What the adaptive loops (integrators/adaptive_loops.hpp) share, written
// once: the run's state (y, the accepted state before it, t, the step h to
// try next), its start and end checks, the trial step towards the next
// output, the rules for an attempt that fails or goes beyond the model's
// limits, and what becomes of an accepted step (its end check, its path
// check, the outputs it reached, clamped or dense). A loop adds only how its
// stepper protocol attempts a step.
//
// Every call that ends the run keeps its result (result()); the loop then
// leaves, as step_ahead() says no more, or attempt() false.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <optional>
#include <utility>
#include <vector>

#include "integrators/driver.hpp"

namespace rb {

class AdaptiveRun {
 public:
  // Throws InputError for bad tolerances (tolerances_of) or output times.
  AdaptiveRun(const Problem& problem, const RunOptions& options)
      : problem_(problem),
        tol_(tolerances_of(options)),
        book_(problem, options),
        h_given_(options.h),
        t_end_(book_.outputs().back()),
        y_(problem.y0()),
        y_before_(y_) {}

  Cost& cost() { return book_.cost(); }
  const FlatState& y() const { return y_; }  // the current state, at t()
  double t() const { return t_; }
  double h() const { return h_; }          // the step the controller proposes
  double t_end() const { return t_end_; }  // the last output time
  // The trial step (step_ahead): h_try() from t() towards bound(), the next
  // output (t_end for a dense stepper), landing on it when lands().
  double h_try() const { return h_try_; }
  double bound() const { return bound_; }

  // The start: tolerances a controller can meet (attainable) and a start
  // within the model (one evaluation), else the run ends there; then the
  // first step: options.h, or automatic() when that is 0.
  template <class Automatic>
  void start(Automatic&& automatic) {
    if (const Validity v = attainable(tol_, y_); v.status != Status::ok)
      return (void)end(book_.stop(v.status, v.reason, y_, t_));
    if (const Validity v = book_.check_model_at(y_, t_); v.status != Status::ok)
      return (void)end(book_.stop(v.status, v.reason, y_, t_));
    h_ = h_given_ > 0.0 ? h_given_ : automatic();
  }
  // initial_step from the current state for a method of the given order.
  double automatic_step(int order) { return initial_step(problem_, y_, tol_, order, t_end_, cost()); }

  // Whether the run takes another step: not once it has ended or recorded
  // its last output; it ends over the step budget or when h fell below
  // min_step_at (or is NaN). Else sets the trial: steps land on bound when
  // within reach, a remainder below min_step_at taken in this step rather
  // than alone.
  bool step_ahead(bool dense_output) {
    const std::vector<double>& outputs = book_.outputs();
    if (result_ || next_ >= outputs.size()) return false;
    if (book_.over_budget()) return end(book_.stop_over_budget(y_, t_));
    if (!(h_ >= min_step_at(t_))) return end(book_.stop(Status::step_underflow, underflow_message(h_, t_), y_, t_));
    bound_ = dense_output ? t_end_ : outputs[next_];
    lands_ = t_ + h_ >= bound_ - min_step_at(bound_);
    h_try_ = lands_ ? bound_ - t_ : h_;
    limit_ = Validity();
    cost().watch.speed2 = 0.0;  // the attempt's stages' own
    return true;
  }

  // Runs one attempt (try_one()). A failure it throws ends the run at y
  // (a StepFailure with its status, another exception as Status::error)
  // and gives false, unless the attempt's stages went beyond a limit (an
  // implicit solve iterating there, a library's error): that is the limit's
  // refusal, after back_to_y() (a library's stepper goes back to y).
  template <class TryOne, class BackToY>
  bool attempt(TryOne&& try_one, BackToY&& back_to_y) {
    auto failed_at_limit = [&] {
      if (!cost().watch.beyond) return false;
      limit_ = book_.stage_limit();
      if (limit_.status == Status::ok) return false;
      back_to_y();
      return true;
    };
    try {
      try_one();
    } catch (const StepFailure& e) {
      if (!failed_at_limit()) return end(book_.stop(e.status(), e.what(), y_, t_));
    } catch (const std::exception& e) {
      if (!failed_at_limit()) return end(book_.stop(Status::error, e.what(), y_, t_));
    } catch (...) {
      return end(book_.stop(Status::error, "unknown exception from the stepper", y_, t_));
    }
    return true;
  }

  // Whether a stage of the attempt just made went beyond the model's limits
  // (Cost::watch): the attempt is then refused, whatever else it found.
  bool beyond_limit() {
    if (cost().watch.beyond) [[unlikely]]
      limit_ = book_.stage_limit();
    return limit_.status != Status::ok;
  }

  // After an attempt of the trial step: refused at a limit, rejected (the
  // controller proposing h_next), or accepted and kept. A step shortened to
  // land says little about the next one: the controller's previous proposal
  // stays when it was larger.
  template <class Stepper>
  void settle(Stepper& stepper, bool accepted, double h_next) {
    if (limit_.status != Status::ok) [[unlikely]]
      return refuse(limit_, h_try_, InStep::stage);
    if (!accepted) {
      ++cost().rejected;
      h_ = h_next;
      return;
    }
    keep(stepper, lands_ ? bound_ : t_ + h_try_, lands_ ? std::max(h_next, h_) : h_next, lands_);
  }
  // After an attempt of a stepper that chose its own step and landing, an
  // accepted step to t_new (refused at a limit as a step of that length).
  template <class Stepper>
  void settle_landed(Stepper& stepper, double t_new, double h_next) {
    if (limit_.status != Status::ok) [[unlikely]]
      return refuse(limit_, t_new > t_ ? t_new - t_ : h_try_, InStep::stage);
    keep(stepper, t_new, h_next, t_new >= bound_);
  }

  // The run's result: how it ended, or at its last output the last state's
  // check (one evaluation: no step starts from it) and its end there.
  RunResult result() {
    if (result_) return std::move(*result_);
    if (const Validity v = book_.check_model_at(y_, t_); v.status != Status::ok)
      return book_.stop_before(v, y_before_, t_before_);
    return book_.finish(y_, t_);
  }

 private:
  bool end(RunResult&& result) {
    result_.emplace(std::move(result));
    return false;
  }

  // A step (of h_tried from y) refused for a limit (curvature, lift-off):
  // if y itself is beyond it, the run ends at the state before; else the
  // step shrinks by kLimitShrink, and the run stops at y only when the limit
  // is still met at the smallest step time resolves. From the first such
  // refusal on (as from the first stage near the curvature limit,
  // StageWatch::near), every accepted step's path is checked, however short
  // (path_kept), and kept to kNearLimitTravel: the run is where a limit is.
  void refuse(const Validity& limit, double h_tried, InStep where) {
    check_paths_ = true;
    if (!y_checked_) {
      if (const Validity at = book_.check_model_at(y_, t_); at.status != Status::ok)
        return (void)end(book_.stop_before(at, y_before_, t_before_));
      y_checked_ = true;
    }
    ++cost().rejected;
    if (!(h_tried > min_step_at(t_)))
      return (void)end(book_.stop(limit.status, step_stop_reason(limit, t_, h_tried, where), y_, t_));
    h_ = std::max(kLimitShrink * h_tried, min_step_at(t_));
  }

  // An accepted step to t_new (h_next proposed next; landed: on the
  // trial's bound). A step to a non-finite state or out of the domain ends
  // the run at y, with no output towards it (the model's limits were tested
  // at every stage); one whose path fails its check is undone; else the
  // outputs it reached are recorded and it becomes the current state. The
  // path is checked (path_kept) for every step that moved the contact point
  // more than kPathSpacing radii (short_step: from its chord and its stages'
  // speeds; a shorter one is covered by its stages and the evaluations at
  // its ends, by the steps from them), and for every step near a limit.
  template <class Stepper>
  void keep(Stepper& stepper, double t_new, double h_next, bool landed) {
    ++cost().steps;
    const double t_old = t_;
    t_ = t_new;
    h_ = h_next;
    stepper.state(y_new_);
    if (const Validity v = problem_.check_step(y_new_); v.status != Status::ok)
      return (void)end(book_.stop(v.status, v.reason, y_, t_old));
    const bool near = check_paths_ || cost().watch.near;
    const double chord2 = (contact_of(y_new_) - contact_of(y_)).squaredNorm();
    const bool checked = near || !short_step(chord2, t_ - t_old, cost().watch.speed2, radius_);
    if (checked) [[unlikely]]
      if (!path_kept(stepper, t_old, near)) return;
    if constexpr (Stepper::dense_output) {
      if (!record_dense(stepper, t_old)) return;
    } else if (landed) {
      book_.output().push(t_, y_new_);
      ++next_;
    }
    y_before_ = y_;
    t_before_ = t_old;
    y_ = y_new_;
    y_checked_ = false;
    if (checked) [[unlikely]] {
      slope_y_ = slope_new_;
    } else {
      slope_y_.known = false;
    }
  }

  // Undoes the step just kept from t_old (refused after the fact): the
  // stepper back to y; gives the step's length.
  template <class Stepper>
  double undo(Stepper& stepper, double t_old) {
    stepper.restore(y_);
    --cost().steps;
    const double h_tried = t_ - t_old;
    t_ = t_old;
    return h_tried;
  }

  // A path beyond a limit between the stages (check_step_path, with F(y)
  // from the check of the step before when it had one, and at least
  // kPathPointsMin points near a limit), or, near a limit, a step too long
  // to resolve the landscape there (kNearLimitTravel): the step is undone
  // and refused, or retried at the length that moves the contact point half
  // as far. Whether the step stays (then F at its end is slope_new_).
  template <class Stepper>
  bool path_kept(Stepper& stepper, double t_old, bool near) {
    const PathCheck path = check_step_path(problem_, y_, y_new_, t_ - t_old, cost(), slope_y_,
                                           std::sqrt(cost().watch.speed2), near ? kPathPointsMin : 0);
    const double reach = kNearLimitTravel * radius_;
    if (path.limit.status == Status::ok && !(near && path.travel > reach)) {
      slope_new_ = path.end;
      return true;
    }
    const double h_tried = undo(stepper, t_old);
    if (path.limit.status != Status::ok) {
      refuse(path.limit, h_tried, InStep::path);
    } else {
      ++cost().rejected;
      h_ = h_tried * 0.5 * reach / path.travel;
    }
    return false;
  }

  // Records every output the step from t_old reached, interpolated by the
  // stepper's dense output. A non-finite interpolant (the dense output can
  // see what the step's end did not) ends the run at the last row; a row
  // between the step's stages is a state the run reports, checked as a
  // stage is (one evaluation, counted): beyond a limit, the step's rows go,
  // the step is undone and refused. Whether the step stays.
  template <class Stepper>
  bool record_dense(Stepper& stepper, double t_old) {
    const std::vector<double>& outputs = book_.outputs();
    Trajectory& out = book_.output();
    const std::size_t rows_before = out.t.size(), next_before = next_;
    Validity row_limit;
    for (; next_ < outputs.size() && outputs[next_] <= t_; ++next_) {
      const double t_out = outputs[next_];
      if (t_out == t_) {
        y_out_ = y_new_;
      } else {
        stepper.interpolate(t_out, y_out_);
      }
      if (const Validity at = problem_.check_step(y_out_); at.status != Status::ok) {
        const bool none = out.y.empty();
        return end(book_.stop(at.status, at.reason, none ? y_ : out.y.back(), none ? t_old : out.t.back()));
      }
      if (t_out != t_) {
        cost().note(problem_.model().margins_at(y_out_));
        if (cost().watch.beyond && (row_limit = book_.stage_limit()).status != Status::ok) break;
      }
      out.push(t_out, y_out_);
    }
    if (row_limit.status == Status::ok) [[likely]]
      return true;
    out.t.resize(rows_before);
    out.y.resize(rows_before);
    next_ = next_before;
    refuse(row_limit, undo(stepper, t_old), InStep::stage);
    return false;
  }

  const Problem& problem_;
  const double radius_ = problem_.model().params().radius;
  const Tolerances tol_;
  RunBook book_;
  const double h_given_;  // options.h: the first step, or 0 for automatic
  const double t_end_;
  std::optional<RunResult> result_;  // set when the run has ended
  FlatState y_;
  double t_ = 0.0, h_ = 0.0;
  // the accepted state before y, where a run ends whose y is found beyond a
  // limit; and whether y is known to be within them
  FlatState y_before_;
  double t_before_ = 0.0;
  bool y_checked_ = true;
  bool check_paths_ = false;  // see refuse
  std::size_t next_ = 0;      // the next output to record
  // the trial (step_ahead) and a limit its attempt met
  double bound_ = 0.0, h_try_ = 0.0;
  bool lands_ = false;
  Validity limit_;
  FlatState y_new_, y_out_;  // reused: no allocation in the loop
  // F at y, when the path check of the step that reached it evaluated it;
  // F at y_new, from the check of the step to it
  PathSlope slope_y_, slope_new_;
};

}  // namespace rb

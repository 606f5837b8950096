#pragma once
// The loop every fixed-step method shares: uniform steps of about h that land
// exactly on each output time, the per-step validity check, the full check at
// outputs, the step budget, and the bookkeeping of a run that stops early.
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"
#include "problems/input_error.hpp"

namespace rb {

// A tableau's non-zero coefficients, gathered once per run so that the step
// loops of the tableau methods (runge_kutta.cpp, munthe_kaas.cpp) skip the
// zeros without testing them and read no std::vector in the step.
struct StageTerms {
  struct Row {
    int count = 0;                          // non-zero terms
    std::array<int, kMaxStages> index{};    // j of each term, increasing
    std::array<double, kMaxStages> coeff{}; // a_ij (or b_j) of each term
    void add(int j, double value) {
      if (value == 0.0) return;
      index[static_cast<std::size_t>(count)] = j;
      coeff[static_cast<std::size_t>(count)] = value;
      ++count;
    }
    // out = base + h c_0 k[j_0] + h c_1 k[j_1] + ...: for up to four terms
    // one pass over the vector with the sums in registers, instead of one
    // pass per term through memory; the same additions in the same order.
    // out must not be one of the k. Inlined: a call would pass the sum
    // through memory once more.
    template <class V, class K>
    [[gnu::always_inline]] void sum(V& out, const V& base, double h, const K& k) const {
      const auto term = [&](std::size_t n) { return (h * coeff[n]) * k[static_cast<std::size_t>(index[n])]; };
      switch (count) {
        case 0: out = base; break;
        case 1: out.noalias() = base + term(0); break;
        case 2: out.noalias() = base + term(0) + term(1); break;
        case 3: out.noalias() = base + term(0) + term(1) + term(2); break;
        default:
          out.noalias() = base + term(0) + term(1) + term(2) + term(3);
          for (std::size_t n = 4; n < static_cast<std::size_t>(count); ++n) out += term(n);
      }
    }
    // The same without a base: h c_0 k[j_0] + h c_1 k[j_1] + ... (0 if none).
    template <class V, class K>
    [[gnu::always_inline]] void sum(V& out, double h, const K& k) const {
      const auto term = [&](std::size_t n) { return (h * coeff[n]) * k[static_cast<std::size_t>(index[n])]; };
      switch (count) {
        case 0: out.setZero(); break;
        case 1: out.noalias() = term(0); break;
        case 2: out.noalias() = term(0) + term(1); break;
        case 3: out.noalias() = term(0) + term(1) + term(2); break;
        default:
          out.noalias() = term(0) + term(1) + term(2) + term(3);
          for (std::size_t n = 4; n < static_cast<std::size_t>(count); ++n) out += term(n);
      }
    }
  };
  int stages;
  std::array<Row, kMaxStages> a;  // row i: the terms of stage i
  Row b;                          // the weights

  explicit StageTerms(const Tableau& tableau) : stages(tableau.stages()) {
    for (int i = 0; i < stages; ++i)
      for (int j = 0; j < i; ++j) a[static_cast<std::size_t>(i)].add(j, tableau.a(i, j));
    for (int j = 0; j < stages; ++j) b.add(j, tableau.b(j));
  }
};

// The output times of a run: options.output_times with t_end appended when
// missing. Throws InputError when they are not increasing within (0, t_end].
std::vector<double> output_times_of(const Problem& problem, const RunOptions& options);

// The effective end time of a run.
inline double t_end_of(const Problem& problem, const RunOptions& options) {
  return options.t_end > 0.0 ? options.t_end : problem.t_end();
}

// The model's validity (lift-off, curvature: Problem::check_model) at every
// accepted step. A step that can, hands the driver the margins of its own
// start state from its first stage (see drive_fixed_step); the driver
// checks them, and each state is checked once, the last one by one extra
// evaluation at the end. ModelCheck keeps the count and the reason.
std::string model_stop_reason(const Validity& v, double t);

// Runs step(y, t, h, cost) repeatedly. step advances y in place from t to
// t + h and adds its own counts (rhs_evals, exp_evals, ...) to cost; the
// driver counts steps. A step may instead take (y, next, t, h, cost) and
// write the state at t + h into next, leaving y as it is: that saves copying
// the state twice a step on the critical path of a cheap step. A step that
// takes (y, next, t, h, cost, margins) also fills margins at y from its
// first stage (the right-hand side there computes them anyway): then the
// model's validity of y is decided at no extra evaluation, one step late,
// and a state found invalid is dropped with its output row. Other steps
// get an explicit check of each new state (Problem::check_full). Either
// way every accepted state and the start are checked once, counted in
// Cost::validity_checks. Between two outputs t_a < t_b it takes
// n = ceil((t_b - t_a) / h) equal steps, so h is kept exactly when the
// output spacing is a multiple of h.
template <class StepFn>
RunResult drive_fixed_step(const Problem& problem, const RunOptions& options, StepFn&& step) {
  constexpr bool gives_margins =
      std::is_invocable_v<StepFn&, const FlatState&, FlatState&, double, double, Cost&, ModelMargins&>;
  constexpr bool writes_next = std::is_invocable_v<StepFn&, const FlatState&, FlatState&, double, double, Cost&>;
  if (!(options.h > 0.0) || !std::isfinite(options.h))
    throw InputError("a fixed-step method needs a step h > 0", "h");
  const std::vector<double> outputs = output_times_of(problem, options);
  RunResult run;
  run.output.t.reserve(outputs.size());
  run.output.y.reserve(outputs.size());
  // the state before the current one, the current one and the next,
  // rotated after each accepted step (the one before is where a run whose
  // current state fails its deferred check ends)
  std::array<FlatState, 3> states = {problem.y0(), problem.y0(), FlatState()};
  FlatState* before = &states[0];
  FlatState* y = &states[1];
  FlatState* next = &states[2];
  double t_before = 0.0, t = 0.0;
  // moved out, not copied: the rows may be many
  auto stop = [&](const Validity& v, const FlatState& last_valid, double t_valid) {
    return std::move(run.stopped(v.status, v.reason, last_valid, t_valid));
  };
  // the current state failed the model's check: end at the one before,
  // without the current state's output row
  auto stop_model = [&](const Validity& v) {
    if (!run.output.t.empty() && run.output.t.back() == t && t > t_before) {
      run.output.t.pop_back();
      run.output.y.pop_back();
    }
    return stop({v.status, model_stop_reason(v, t)}, *before, t_before);
  };
  if constexpr (!gives_margins) {
    ++run.cost.validity_checks;
    if (const Validity v = problem.check_full(*y); v.status != Status::ok) return stop_model(v);
  }
  for (const double t_out : outputs) {
    const double span = t_out - t;
    // the slack absorbs the rounding of span on long runs with dense output
    // (t ~ 10, span ~ 1e-5 has a relative error ~ 1e-10), which would add
    // a step to an interval that h divides; the cost is steps at most 1e-6
    // longer than h
    const double n_real = std::ceil(span / options.h - 1e-6);
    if (n_real > 1e15) return stop({Status::max_steps, "the step count overflows"}, *y, t);
    const long n = std::max(1L, static_cast<long>(n_real));
    const double h = span / static_cast<double>(n);
    const double t_start = t;
    for (long i = 0; i < n; ++i) {
      if (run.cost.steps + run.cost.rejected >= options.max_steps)
        return stop({Status::max_steps, "reached max_steps = " + std::to_string(options.max_steps)}, *y, t);
      if constexpr (gives_margins) {
        ModelMargins margins;
        step(std::as_const(*y), *next, t, h, run.cost, margins);
        ++run.cost.validity_checks;
        if (!problem.within_model(margins)) [[unlikely]]
          return stop_model(problem.check_model(margins));
      } else if constexpr (writes_next) {
        step(std::as_const(*y), *next, t, h, run.cost);
      } else {
        *next = *y;
        step(*next, t, h, run.cost);
      }
      ++run.cost.steps;
      const Validity v = problem.check_step(*next);
      if (v.status != Status::ok) return stop(v, *y, t);
      const double t_next = (i + 1 == n) ? t_out : t_start + static_cast<double>(i + 1) * h;
      if constexpr (!gives_margins) {
        ++run.cost.validity_checks;
        if (const Validity m = problem.check_full(*next); m.status != Status::ok)
          return stop({m.status, model_stop_reason(m, t_next)}, *y, t);
      }
      FlatState* const freed = before;
      before = y;
      y = next;
      next = freed;
      t_before = t;
      t = t_next;
    }
    run.output.push(t, *y);
  }
  if constexpr (gives_margins) {
    // the last state: no step starts from it, so one evaluation of its own
    ++run.cost.validity_checks;
    if (const Validity v = problem.check_full(*y); v.status != Status::ok) return stop_model(v);
  }
  run.final_state = *y;
  run.stop_time = t;
  return run;
}

}  // namespace rb

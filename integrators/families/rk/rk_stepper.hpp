#pragma once
// Classical explicit Runge-Kutta on the flat view y in R^14, for any
// tableau: the one stepper of the rk family, at fixed steps (family "rk")
// and on an embedded pair (family "rk-adaptive"; the flat twins of the RKMK
// pairs). R drifts off SO(3). rk_method (runge_kutta.cpp) makes both from
// with_rk_stepper below.
//
// One stage loop, step<Estimate>:
// - Estimate = false, a fixed step (drive_fixed_step's functor,
//   integrators/driver.hpp): the stages b weights (tableau.stages());
// - Estimate = true, an adaptive attempt (the EmbeddedPair protocol,
//   integrators/steppers/embedded_pair.hpp, driven by drive_estimating):
//   also the stages only the error weights use (tableau.attempt_stages()),
//   and the error norm of error_norm.hpp: the local error
//   h e_0 k_0 + h e_1 k_1 + ..., each component against
//   atol + rtol max(|y_n,i|, |y_n+1,i|), root mean square (Hairer's).
// Both sum every stage and the new state with StageTerms::Row::sum,
// y + (h c_0) k_0 + (h c_1) k_1 + ..., so that a pair's new state is its
// tableau's fixed step bit for bit.
//
// The pair has no dense output: steps are clamped to land on every output
// time. FSAL where the tableau's error weights use its FSAL stage (BS32,
// DP54): that stage is at y_new itself (its row of A is b, so its sum is
// the new state's), and its right-hand side starts the next step;
// otherwise the next attempt evaluates F(y_new).
#include <array>
#include <cstddef>

#include "integrators/integrator.hpp"
#include "integrators/stage_terms.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"
#include "integrators/tableau.hpp"

namespace rb {

// S: the tableau's stages() when known at compile time, 0 for any. With S
// known a fixed step's stage loop unrolls around the inlined right-hand
// side, and the compiler schedules each stage's sum into the tail of the
// evaluation before it (about a tenth of an RK4 step on valley-sideways).
// An attempt's loop runs to attempt_stages(), known at run time.
template <int S>
class RkStepper : public EmbeddedPair<RkStepper<S>> {
 public:
  static constexpr bool dense_output = false;

  // tol: the pair's tolerances (none at fixed steps). The problem and the
  // tableau must outlive the stepper.
  RkStepper(const Problem& problem, const Tableau& tableau, const Tolerances& tol = {})
      : problem_(&problem), tableau_(&tableau), tol_(tol), y_(problem.y0()), terms_(tableau) {}

  // One step of h from y into next; Estimate: also the error norm of the
  // step (its first stage k_0 = F(y) already evaluated), else 0. Every
  // stage's validity margins are noted in cost (stage_flat_rhs).
  template <bool Estimate>
  [[gnu::always_inline]] double step(const FlatState& y, FlatState& next, double h, Cost& cost) {
    // Estimate: also the stages only the error weights use
    const int stages = Estimate ? terms_.attempt : S > 0 ? S : terms_.stages;
    if constexpr (!Estimate) stage_flat_rhs(*problem_, y.data(), k_[0].data(), cost);
    for (int i = 1; i < stages; ++i) {
      const StageTerms::Row& row = terms_.a[static_cast<std::size_t>(i)];
      // the stage's state, y + h a_i0 k_0 + h a_i1 k_1 + ... (the non-zero
      // terms); with none y itself, uncopied
      const FlatState* at = &y;
      if (row.count > 0) {
        row.sum(Y_, y, h, k_);
        at = &Y_;
      }
      stage_flat_rhs(*problem_, at->data(), k_[static_cast<std::size_t>(i)].data(), cost);
    }
    terms_.b.sum(next, y, h, k_);
    if constexpr (Estimate) {
      cost.rhs_evals += stages - 1;  // k_0 is first_stage's
      return error_norm(y, next, h);
    } else {
      cost.rhs_evals += stages;
      return 0.0;
    }
  }

  // drive_fixed_step's functor: a fixed step.
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    step<false>(y, next, h, cost);
  }

  // The EmbeddedPair protocol (the pair's state is y_).
  int error_order() const { return tableau_->error_order(); }
  void first_stage(Cost& cost) {
    stage_flat_rhs(*problem_, y_.data(), k_[0].data(), cost);
    ++cost.rhs_evals;
  }
  double attempt(double h, Cost& cost) { return step<true>(y_, y_new_, h, cost); }
  bool tried_finite() const { return y_new_.allFinite(); }
  // the next step's first stage: the FSAL stage, or evaluated by the next
  // attempt (so that its margins are that attempt's)
  bool commit(double /*t*/, double /*h*/, Cost& /*cost*/) {
    y_ = y_new_;
    if (!tableau_->fsal_in_attempt()) return false;
    k_[0] = k_[static_cast<std::size_t>(*tableau_->fsal_stage())];
    return true;
  }
  void state(FlatState& y) const { y = y_; }
  void interpolate(double, FlatState& y) const { y = y_; }
  void go_back(const FlatState& y) { y_ = y; }

 private:
  // out of the stage loop's function: inlined there, GCC left more of
  // Eigen's sums as calls (rk-dp54-adaptive 28 instructions a step more,
  // callgrind)
  [[gnu::noinline]] double error_norm(const FlatState& y, const FlatState& next, double h) {
    terms_.e.sum(error_, h, k_);
    return rms_error(scaled_squares(error_, value_scale(tol_, y, next)), kFlatSize);
  }

  const Problem* problem_;
  const Tableau* tableau_;
  Tolerances tol_;
  FlatState y_, y_new_, Y_, error_;
  StageTerms terms_;
  std::array<FlatState, kMaxStages> k_;
};

// drive(stepper) with the tableau's stepper for one run: for a pair
// (Pair = true, with the run's tolerances) or at fixed steps (tol: none),
// the fixed steps' stage loop unrolled for the registry's tableaus (1 to 4
// stages; the larger ones go generic, as do the attempts).
template <bool Pair, class Drive>
auto with_rk_stepper(const Problem& problem, const Tableau& tableau, const Tolerances& tol, Drive&& drive) {
  const auto run = [&]<int S>() {
    RkStepper<S> stepper(problem, tableau, tol);
    return drive(stepper);
  };
  if constexpr (Pair) {
    return run.template operator()<0>();
  } else {
    switch (tableau.stages()) {
      case 1: return run.template operator()<1>();
      case 2: return run.template operator()<2>();
      case 3: return run.template operator()<3>();
      case 4: return run.template operator()<4>();
      default: return run.template operator()<0>();
    }
  }
}

}  // namespace rb

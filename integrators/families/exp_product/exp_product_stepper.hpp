#pragma once
// The one stepper of the exponential-product schemes (exp_product_scheme.hpp:
// the commutator-free and Crouch-Grossman methods), at fixed steps and on an
// embedded pair alike (exp_product_method, exp_product.hpp, makes both): the
// scheme planned once, and ONE stage loop, step<Estimate>:
// - Estimate = false, the fixed step (drive_fixed_step, integrators/driver.hpp):
//   the stages the update reads (ExpPlan::propagating) and the update.
// - Estimate = true, an attempt of the pair (EmbeddedPair's protocol, driven
//   by drive_estimating, integrators/adaptive_loops.hpp): every stage (the
//   embedded update's too), the same update with the same arithmetic (so the
//   new state is the fixed step's bit for bit), the embedded update and the
//   error norm:
//   - R: the rotation vector of R_high R_low^T, taken as vee of its skew part
//     (sin(angle) axis: equal to O(angle^3), and the angle is the error's
//     size), against atol + rtol (R's entries are of size 1, as a flat
//     method sees them); z componentwise against atol + rtol max(|z_n,i|,
//     |z_n+1,i|). Root mean square over the 3 + 5 components
//     (steppers/error_norm.hpp).
//   - No dense output: steps are clamped to land on every output time.
// Cost of a fixed step: (propagating - 1) rhs evaluations after the first
// stage, the stage exponentials on an anisotropic ball and the update's; of
// an attempt: (stages - 1) rhs evaluations (the first stage once per
// accepted step), the stage exponentials on an anisotropic ball and the
// exponentials of both updates.
#include <array>
#include <limits>

#include "integrators/driver.hpp"
#include "integrators/families/exp_product/exp_product_scheme.hpp"
#include "integrators/stage_terms.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"
#include "problems/so3.hpp"

namespace rb {

using ExpRow = StageTerms::Row;

// A product as the step runs it: its non-zero factors, and the stage whose
// orientation is the product of its first factors (CF4's Y_4 continues
// from Y_2), so that no exponential is computed twice.
struct PlannedProduct {
  int base = -1;  // -1: R_n itself
  int count = 0;
  std::array<ExpRow, kMaxStages> factor;  // the rest, in the order applied
};

struct ExpPlan {
  int stages = 0;       // all of them (an attempt of the pair computes these)
  int propagating = 0;  // the first ones, those the update reads (a fixed step computes these)
  std::array<PlannedProduct, kMaxStages> stage;
  std::array<ExpRow, kMaxStages> z_stage;  // Z_i - z = h sum over stage i's factors
  PlannedProduct update;                   // R_{n+1}
  ExpRow z_update;
  PlannedProduct embedded;  // the embedded update (count 0: the scheme has none)
  ExpRow z_embedded;
  int error_order = 0;  // min(order, embedded order) + 1 (0: no embedded update)
};

// Throws std::invalid_argument for a malformed scheme (a stage using a field
// not yet computed, too many stages or factors, an empty update).
ExpPlan plan_of(const ExpProductScheme& scheme);

class ExpProductStepper : public EmbeddedPair<ExpProductStepper> {
 public:
  static constexpr bool dense_output = false;

  // tol: the error norm's (none for fixed steps). plan must outlive the stepper.
  ExpProductStepper(const Problem& problem, const ExpPlan& plan, const Tolerances& tol = {})
      : problem_(&problem),
        plan_(&plan),
        anisotropic_(problem.model().anisotropic()),
        tol_(tol),
        R_(rotation_of(problem.y0())),
        z_(z_of(problem.y0())) {}

  // The fixed step (drive_fixed_step); every stage's validity margins are
  // noted in cost (stage_lie_rhs)
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    const ZState z = z_of(y);
    const Mat3 R = rotation_of(y);
    first_stage_at(R, z, cost);
    Mat3 R_new;
    ZState dz;
    step<false>(R, z, h, R_new, dz, cost);
    set_rotation(next, R_new);
    next.tail<kZSize>() = z + dz;
  }

  // The step of h from (R, z), stage 1 already in K_[0], L_[0]: R_{n+1} in
  // R_new, z_{n+1} - z in dz; with Estimate, the error norm (NaN when the
  // step is not finite), else 0.
  template <bool Estimate>
  double step(const Mat3& R, const ZState& z, double h, Mat3& R_new, ZState& dz, Cost& cost) {
    later_stages(R, z, h, Estimate ? plan_->stages : plan_->propagating, cost);
    plan_->z_update.sum(dz, h, L_);
    R_new = apply(plan_->update, R, h, cost);
    if constexpr (!Estimate) {
      return 0.0;
    } else {
      const Mat3 R_low = apply(plan_->embedded, R, h, cost);
      ZState dz_low;
      plan_->z_embedded.sum(dz_low, h, L_);
      finite_ = R_new.allFinite() && dz.allFinite() && R_low.allFinite() && dz_low.allFinite();
      if (!finite_) return std::numeric_limits<double>::quiet_NaN();
      // vee of the skew part of R_high R_low^T
      const Mat3 D = R_new * R_low.transpose();
      const Vec3 e_rot(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
      const double rotation = (0.5 * e_rot / rotation_scale(tol_)).squaredNorm();
      return rms_error(rotation + scaled_squares(ZState(dz - dz_low), value_scale(tol_, z, ZState(z + dz))),
                       3 + kZSize);
    }
  }

  // The pair's protocol (steppers/embedded_pair.hpp): the state is (R_, z_)
  int error_order() const { return plan_->error_order; }
  void first_stage(Cost& cost) { first_stage_at(R_, z_, cost); }
  // the step kept in R_new_, dz_new_ for commit
  double attempt(double h, Cost& cost) { return step<true>(R_, z_, h, R_new_, dz_new_, cost); }
  bool tried_finite() const { return finite_; }
  // the next attempt starts at the new state
  bool commit(double /*t*/, double /*h*/, Cost& /*cost*/) {
    R_ = R_new_;
    z_ += dz_new_;
    return false;
  }
  void state(FlatState& y) const {
    set_rotation(y, R_);
    y.tail<kZSize>() = z_;
  }
  void interpolate(double, FlatState& y) const { state(y); }
  // state() wrote y from R_ and z_, so they come back bit for bit
  void go_back(const FlatState& y) {
    R_ = rotation_of(y);
    z_ = z_of(y);
  }

 private:
  void first_stage_at(const Mat3& R, const ZState& z, Cost& cost) {
    stage_lie_rhs(*problem_, R, z.data(), K_[0].data(), L_[0].data(), cost);
    ++cost.rhs_evals;
  }

  // the product p applied to R (stage orientations already in Rs_)
  Mat3 apply(const PlannedProduct& p, const Mat3& R, double h, Cost& cost) const {
    Mat3 M = p.base < 0 ? R : Rs_[static_cast<std::size_t>(p.base)];
    for (std::size_t n = 0; n < static_cast<std::size_t>(p.count); ++n) {
      Vec3 U;
      p.factor[n].sum(U, h, K_);
      M = so3_exp(U) * M;
    }
    cost.exp_evals += p.count;
    return M;
  }

  // stages 2 .. stages from (R, z), stage 1 already in K_[0], L_[0]
  void later_stages(const Mat3& R, const ZState& z, double h, int stages, Cost& cost) {
    for (std::size_t i = 1; i < static_cast<std::size_t>(stages); ++i) {
      ZState Z;
      plan_->z_stage[i].sum(Z, z, h, L_);
      if (anisotropic_) {
        // R enters omega and G: evaluate at the stage's own orientation
        Rs_[i] = apply(plan_->stage[i], R, h, cost);
        stage_lie_rhs(*problem_, Rs_[i], Z.data(), K_[i].data(), L_[i].data(), cost);
      } else {
        stage_lie_rhs(*problem_, R, Z.data(), K_[i].data(), L_[i].data(), cost);
      }
    }
    cost.rhs_evals += stages - 1;
  }

  const Problem* problem_;
  const ExpPlan* plan_;
  bool anisotropic_;  // stage orientations needed
  Tolerances tol_;
  std::array<Vec3, kMaxStages> K_;    // omega at the stages
  std::array<ZState, kMaxStages> L_;  // z' at the stages
  std::array<Mat3, kMaxStages> Rs_;   // the stage orientations
  Mat3 R_, R_new_;                    // the pair's state and its tried step
  ZState z_, dz_new_;
  bool finite_ = false;  // the step tried last is finite
};

}  // namespace rb

#pragma once
// The step of an exponential-product scheme (integrators/families/exp_product/exp_product_scheme.hpp)
// as both the fixed-step method (exp_product.cpp) and its adaptive pair
// (exp_product_adaptive.cpp) run it:
// the scheme planned once, the stages, and a product applied to R_n.
#include <array>

#include "integrators/driver.hpp"
#include "integrators/families/exp_product/exp_product_scheme.hpp"
#include "integrators/stage_terms.hpp"
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
  int stages = 0;
  std::array<PlannedProduct, kMaxStages> stage;
  std::array<ExpRow, kMaxStages> z_stage;  // Z_i - z = h sum over stage i's factors
  PlannedProduct update;                   // R_{n+1}
  ExpRow z_update;
  PlannedProduct embedded;  // the embedded update (count 0: the scheme has none)
  ExpRow z_embedded;
};

// Throws std::invalid_argument for a malformed scheme (a stage using a field
// not yet computed, too many stages or factors, an empty update).
ExpPlan plan_of(const ExpProductScheme& scheme);

struct ExpProductStep {
  const Problem& problem;
  const ExpPlan& plan;
  bool anisotropic;                   // stage orientations needed
  std::array<Vec3, kMaxStages>& K;    // omega at the stages
  std::array<ZState, kMaxStages>& L;  // z' at the stages
  std::array<Mat3, kMaxStages>& Rs;   // the stage orientations

  // the product p applied to R (stage orientations already in Rs)
  Mat3 apply(const PlannedProduct& p, const Mat3& R, double h, Cost& cost) const {
    Mat3 M = p.base < 0 ? R : Rs[static_cast<std::size_t>(p.base)];
    for (std::size_t n = 0; n < static_cast<std::size_t>(p.count); ++n) {
      Vec3 U;
      p.factor[n].sum(U, h, K);
      M = so3_exp(U) * M;
    }
    cost.exp_evals += p.count;
    return M;
  }

  // stages 2 .. s from (R, z), stage 1 already in K[0], L[0]
  void later_stages(const Mat3& R, const ZState& z, double h, Cost& cost) const {
    for (std::size_t i = 1; i < static_cast<std::size_t>(plan.stages); ++i) {
      ZState Z;
      plan.z_stage[i].sum(Z, z, h, L);
      if (anisotropic) {
        // R enters omega and G: evaluate at the stage's own orientation
        Rs[i] = apply(plan.stage[i], R, h, cost);
        stage_lie_rhs(problem, Rs[i], Z.data(), K[i].data(), L[i].data(), cost);
      } else {
        stage_lie_rhs(problem, R, Z.data(), K[i].data(), L[i].data(), cost);
      }
    }
    cost.rhs_evals += plan.stages - 1;
  }

  // The fixed step (drive_fixed_step); every stage's validity margins are
  // noted in cost (stage_lie_rhs)
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) const {
    const ZState z = z_of(y);
    const Mat3 R = rotation_of(y);
    stage_lie_rhs(problem, R, z.data(), K[0].data(), L[0].data(), cost);
    ++cost.rhs_evals;
    later_stages(R, z, h, cost);
    ZState dz;
    plan.z_update.sum(dz, h, L);
    set_rotation(next, apply(plan.update, R, h, cost));
    next.tail<kZSize>() = z + dz;
  }
};

}  // namespace rb

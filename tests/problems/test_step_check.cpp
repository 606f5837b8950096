// The per-step test of the fixed-step driver (Problem::surely_within_step,
// then check_step only when it fails): it must say what check_step says,
// and a NaN must still end the run at the step where it appears.
#include <gtest/gtest.h>

#include <limits>

#include "integrators/driver.hpp"
#include "problems/scene.hpp"

namespace rb {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// domain [-2, 2] x [-2, 12], the homogeneous ball (R enters no right-hand side)
Problem valley() { return make_problem(load_scene("valley-sideways")); }

TEST(StepCheck, SurelyWithinStepIsFalseForEveryNonFiniteEntry) {
  const Problem p = valley();
  EXPECT_TRUE(p.surely_within_step(p.y0()));
  EXPECT_EQ(p.check_step(p.y0()).status, Status::ok);
  for (int i = 0; i < kFlatSize; ++i) {
    for (const double bad : {kNaN, kInf, -kInf}) {
      FlatState y = p.y0();
      y[i] = bad;
      EXPECT_FALSE(p.surely_within_step(y)) << i << " " << bad;
      EXPECT_EQ(p.check_step(y).status, Status::diverged) << i << " " << bad;
    }
  }
  // +inf and -inf in two entries sum to NaN: still caught
  FlatState y = p.y0();
  y[0] = kInf;
  y[1] = -kInf;
  EXPECT_FALSE(p.surely_within_step(y));
}

TEST(StepCheck, OverflowingSumIsAFalseAlarmThatCheckStepClears) {
  const Problem p = valley();
  FlatState y = p.y0();
  y[kOffsetV] = 1e308;
  y[kOffsetV + 1] = 1e308;
  EXPECT_FALSE(p.surely_within_step(y));
  EXPECT_EQ(p.check_step(y).status, Status::ok);
}

TEST(StepCheck, LeavingTheDomainFailsBoth) {
  const Problem p = valley();
  FlatState y = p.y0();
  y[kOffsetAlpha] = 2.5;
  EXPECT_FALSE(p.surely_within_step(y));
  EXPECT_EQ(p.check_step(y).status, Status::domain);
  y[kOffsetAlpha] = 2.0;  // the boundary belongs to the domain
  EXPECT_TRUE(p.surely_within_step(y));
}

// Explicit Euler on the flat view with margins from its one stage, as the
// tableau steppers give them, writing a NaN into R(1, 1) alone at its 10th
// step: no right-hand side of the homogeneous ball reads R, so only the
// per-step check can see it.
TEST(StepCheck, NaNOnlyInRotationEndsTheRunAtTheStepItAppears) {
  const Problem p = valley();
  RunOptions o;
  o.h = 1e-3;
  o.t_end = 0.1;
  int calls = 0;
  auto step = [&](const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    FlatState dy;
    stage_flat_rhs(p, y.data(), dy.data(), cost);
    next = y + h * dy;
    ++cost.rhs_evals;
    if (++calls == 10) next[4] = kNaN;
  };
  const RunResult r = drive_fixed_step(p, o, step);
  EXPECT_EQ(r.status, Status::diverged);
  EXPECT_EQ(r.message, "the state is not finite");
  EXPECT_EQ(calls, 10);
  EXPECT_NEAR(r.stop_time, 9e-3, 1e-15);  // the last valid state, before the NaN
  EXPECT_TRUE(r.final_state.allFinite());
}

}  // namespace
}  // namespace rb

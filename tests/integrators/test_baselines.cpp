// The practitioners' fixes: RK4 with R projected back onto SO(3), and RK4 on
// a unit quaternion. R on SO(3) on every shipped scene, the same z as plain
// RK4 (R never enters G), the projection being what it says, and the cost
// counts. The registry order test checks their order 4.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/families/baselines/baselines.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::every;
using testing::valley;

TEST(Baseline, RegisteredWithTheirFamilies) {
  EXPECT_EQ(find_integrator("rk4-projected").family(), "projection");
  EXPECT_EQ(find_integrator("rk4-quaternion").family(), "quaternion");
  for (const char* name : {"rk4-projected", "rk4-quaternion"}) {
    EXPECT_EQ(find_integrator(name).declared_order(), 4);
    EXPECT_FALSE(find_integrator(name).adaptive());
  }
}

TEST(Baseline, RotationStaysOnSO3OnEveryShippedScene) {
  for (const std::string& name : shipped_scene_names()) {
    const Problem p = make_problem(load_scene(name));
    for (const char* method : {"rk4-projected", "rk4-quaternion"}) {
      const RunResult r = find_integrator(method).integrate(p, every(0.1, p.t_end(), 0.01));
      EXPECT_EQ(r.status, Status::ok) << name << " " << method << ": " << r.message;
      ASSERT_FALSE(r.output.y.empty());
      double worst = 0.0;
      for (const FlatState& y : r.output.y) worst = std::max(worst, rotation_defect(rotation_of(y)));
      EXPECT_LE(worst, 1e-13) << name << " " << method;
      EXPECT_NEAR(rotation_of(r.final_state).determinant(), 1.0, 1e-13) << name << " " << method;
    }
  }
}

// z evolves without R: both baselines advance it exactly as plain RK4 does.
TEST(Baseline, SameZAsPlainRk4AndFourRhsAStep) {
  const RunOptions o = every(0.1, 2.0, 0.01);
  const RunResult plain = find_integrator("rk4").integrate(valley(), o);
  ASSERT_EQ(plain.status, Status::ok);
  for (const char* method : {"rk4-projected", "rk4-quaternion"}) {
    const RunResult r = find_integrator(method).integrate(valley(), o);
    ASSERT_EQ(r.status, Status::ok);
    ASSERT_EQ(r.output.y.size(), plain.output.y.size());
    for (std::size_t i = 0; i < r.output.y.size(); ++i)
      EXPECT_LT((z_of(r.output.y[i]) - z_of(plain.output.y[i])).norm(), 1e-12) << method;
    EXPECT_EQ(r.cost.rhs_evals, 4 * r.cost.steps) << method;
    EXPECT_EQ(r.cost.exp_evals, 0) << method;
    EXPECT_EQ(r.cost.dexpinv_evals, 0) << method;
  }
}

// One step of rk4-projected is the projection of one step of rk4, and the
// projection moves R by about rk4's own drift off SO(3) (order h^5).
TEST(Baseline, ProjectedStepIsTheClosestRotationToTheRk4Step) {
  for (const double h : {0.1, 0.05}) {
    const RunOptions o = every(1.0, h, h);
    const RunResult plain = find_integrator("rk4").integrate(valley(), o);
    const RunResult projected = find_integrator("rk4-projected").integrate(valley(), o);
    const Mat3 R_plain = rotation_of(plain.final_state);
    const Mat3 R = rotation_of(projected.final_state);
    // rk4-projected's Newton-Schulz step and the SVD agree to their rounding
    EXPECT_LT((R - project_to_so3(R_plain)).norm(), 4e-15);
    EXPECT_LT((R - R_plain).norm(), 2.0 * rotation_defect(R_plain) + 1e-15);
  }
}

// The quaternion's rotation converges to the Lie-group solution with order 4.
TEST(Baseline, QuaternionRotationConvergesToRkmk4) {
  RunOptions fine = every(1.0, 1.0, 1e-4);
  const FlatState ref = find_integrator("rkmk4").integrate(valley(), fine).final_state;
  double previous = 0.0;
  for (const double h : {0.04, 0.02, 0.01}) {
    const RunResult r = find_integrator("rk4-quaternion").integrate(valley(), every(1.0, 1.0, h));
    ASSERT_EQ(r.status, Status::ok);
    const double e = testing::end_errors(valley(), r.final_state, ref).rotation;
    if (previous > 0.0) {
      EXPECT_NEAR(std::log2(previous / e), 4.0, 0.3) << "h = " << h;
    }
    previous = e;
  }
}

// Past the landscape's edge the state turns non-finite; neither baseline
// hides that behind its projection or normalisation.
TEST(Baseline, StopDivergedPastTheLandscapesEdge) {
  const Problem p = make_problem(load_scene(std::string(RB_TEST_DATA) + "/stop-nonfinite.json"));
  for (const char* method : {"rk4-projected", "rk4-quaternion"}) {
    const RunResult r = find_integrator(method).integrate(p, every(0.01, p.t_end(), 1e-3));
    EXPECT_EQ(r.status, Status::diverged) << method << ": " << r.message;
    EXPECT_TRUE(r.final_state.allFinite()) << method;
    EXPECT_LT(r.stop_time, p.t_end()) << method;
  }
}

}  // namespace
}  // namespace rb

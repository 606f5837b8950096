// One measure of drift for the report, the stability study and `rollbench
// trajectory` (bench/lib/drift.hpp), against closed forms: scaling the
// momentum v by s scales the kinetic energy by s^2, and R scaled by (1 + e)
// has the defect ||(1 + e)^2 I - I||_F = sqrt(3) ((1 + e)^2 - 1).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bench/lib/drift.hpp"
#include "problems/energy.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace rb {
namespace {

TEST(Drift, EnergyAndRotationDefectAgainstClosedForms) {
  const Problem problem = make_problem(load_scene("plane"));
  const FlatState y0 = problem.y0();
  const Derived start = problem.model().derived(y0);
  const BallParams& b = problem.model().params();
  const double kinetic = start.energy - b.mass * b.gravity * start.centre.z();
  ASSERT_GT(kinetic, 0.0);

  const DriftMeter meter(problem);
  EXPECT_EQ(meter.at(y0).energy, 0.0);
  FlatState faster = y0;
  faster.segment<3>(kOffsetV) *= 1.1;
  EXPECT_NEAR(meter.at(faster).energy, (1.1 * 1.1 - 1.0) * kinetic, 1e-12 * kinetic);

  const double e = 1e-6;
  FlatState stretched = y0;
  set_rotation(stretched, (1.0 + e) * rotation_of(y0));
  const double defect = std::sqrt(3.0) * ((1.0 + e) * (1.0 + e) - 1.0);
  EXPECT_NEAR(meter.at(stretched).rotation_defect, defect, 1e-9 * defect);

  // the largest over the start and the outputs; a non-finite state does not raise it
  Trajectory run;
  run.push(0.5, faster);
  run.push(1.0, stretched);
  FlatState broken = y0;
  broken[0] = std::numeric_limits<double>::quiet_NaN();
  run.push(1.5, broken);
  const Drift largest = largest_drift(problem, run);
  EXPECT_EQ(largest.energy, meter.at(faster).energy);
  EXPECT_EQ(largest.rotation_defect, meter.at(stretched).rotation_defect);
  EXPECT_EQ(largest_drift(problem, Trajectory{}).rotation_defect, start.rotation_defect);
  // the homogeneous ball's H does not read R: at the nearest rotation it is the same number
  EXPECT_EQ(meter.at(stretched).energy_on_group, meter.at(stretched).energy);
  EXPECT_EQ(meter.at(faster).energy_on_group, meter.at(faster).energy);
  EXPECT_EQ(largest.energy_on_group, largest.energy);
}

// The energy at the nearest rotation, H(polar(R), v, alpha), against a
// closed form: for R = Q (I + E), Q a rotation and E symmetric (small), the
// polar factor of R is Q, so the energy there is the real ball's at Q, and
// the flat H is that of a ball whose inertia about the centre, seen from the
// world, is Q (I + E)^-1 (Theta + m r^2) (I + E)^-1 Q^T - m r^2: the two
// differ by 1/2 v^T (A(R) - A(Q)) v, A = T^-1, which the test computes by
// plain inverses (the model takes Sherman-Morrison).
TEST(Drift, EnergyAtTheNearestRotationAgainstAClosedForm) {
  const Problem problem = make_problem(load_scene("chaplygin-valley"));
  const RollingBall& ball = problem.model();
  ASSERT_TRUE(ball.anisotropic());
  const BallParams& b = ball.params();
  const double mr2 = b.mass * b.radius * b.radius;
  FlatState y = problem.y0();
  const Mat3 Q = so3_exp(Vec3(0.4, -0.3, 0.9)) * rotation_of(y);
  set_rotation(y, Q);
  y.segment<3>(kOffsetV) += Vec3(0.02, -0.01, 0.03);
  const Mat3 E = 1e-3 * Mat3{{2.0, 0.5, -1.0}, {0.5, -1.5, 0.3}, {-1.0, 0.3, 1.0}};  // symmetric
  const Mat3 R = Q * (Mat3::Identity() + E);
  FlatState off = y;
  set_rotation(off, R);

  const Vec3 N = ball.derived(y).N, v = momentum_of(y);
  const Mat3 D = (b.inertia->array() + mr2).matrix().asDiagonal();  // Theta + m r^2 in the body frame
  const auto kinetic = [&](const Mat3& inertia_plus) {              // 1/2 v^T (inertia_plus - m r^2 N N^T)^-1 v
    return 0.5 * v.dot((inertia_plus - mr2 * N * N.transpose()).inverse() * v);
  };
  const Mat3 P_inv = (Mat3::Identity() + E).inverse();
  const double at_Q = kinetic(Q * D * Q.transpose()), at_R = kinetic(Q * P_inv * D * P_inv * Q.transpose());
  const double H_Q = flat_energy(ball, y);
  ASSERT_GT(std::abs(at_R - at_Q), 1e-6 * std::abs(at_Q));  // a difference worth measuring

  EXPECT_LT((project_to_so3(R) - Q).norm(), 1e-14);
  EXPECT_NEAR(energy_on_group(ball, off), H_Q, 1e-14 * std::abs(H_Q));
  EXPECT_NEAR(energy_on_group(ball, y), H_Q, 1e-14 * std::abs(H_Q));  // on SO(3): the flat one
  EXPECT_NEAR(flat_energy(ball, off) - H_Q, at_R - at_Q, 1e-9 * std::abs(at_R - at_Q));

  // the meter: both against the start's H, which R0 (a rotation) gives both ways
  const DriftMeter meter(problem);
  const double H0 = ball.derived(problem.y0()).energy;
  const Drift d = meter.at(off);
  EXPECT_NEAR(d.energy, std::abs(flat_energy(ball, off) - H0), 1e-14 * std::abs(H0));
  EXPECT_NEAR(d.energy_on_group, std::abs(H_Q - H0), 1e-14 * std::abs(H0));
  EXPECT_TRUE(std::isnan(energy_on_group(ball, FlatState::Constant(std::numeric_limits<double>::quiet_NaN()))));
}

}  // namespace
}  // namespace rb

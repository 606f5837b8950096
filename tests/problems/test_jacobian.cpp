// The exact Jacobian of the flat view (forward-mode AD through flat_rhs)
// against central finite differences, at random states of four scenes (one
// with an anisotropic ball, where R's nine entries enter F).
#include <gtest/gtest.h>

#include <random>

#include "problems/jacobian.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace rb {
namespace {

// A random state near the scene's start: a random rotation, momentum and
// contact point, small enough offsets to stay where the landscape is smooth
// and the contact regular.
FlatState random_state(const Problem& problem, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const FlatState& y0 = problem.y0();
  const Mat3 R = so3_exp(Vec3(u(rng), u(rng), u(rng)) * 2.0);
  const double scale = problem.model().params().mass * std::pow(problem.model().params().radius, 2);
  const Vec3 v = momentum_of(y0) + scale * Vec3(u(rng), u(rng), u(rng)) * 3.0;
  const Vec2 alpha = contact_of(y0) + Vec2(u(rng), u(rng)) * 0.3;
  return make_flat(R, v, alpha);
}

// dF/dy by central differences, column by column.
FlatJacobian central_differences(const Problem& problem, const FlatState& y) {
  FlatJacobian J;
  for (int j = 0; j < kFlatSize; ++j) {
    const double h = 1e-5 * std::max(1.0, std::abs(y[j]));
    FlatState yp = y, ym = y, fp, fm;
    yp[j] += h;
    ym[j] -= h;
    problem.flat_rhs(yp.data(), fp.data());
    problem.flat_rhs(ym.data(), fm.data());
    J.col(j) = (fp - fm) / (yp[j] - ym[j]);
  }
  return J;
}

class JacobianOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(JacobianOnScene, MatchesCentralDifferencesToOneInAMillion) {
  const Problem problem = make_problem(load_scene(GetParam()));
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 20; ++trial) {
    const FlatState y = random_state(problem, rng);
    FlatJacobian J;
    FlatState f;
    flat_jacobian(problem, y, J, &f);
    const FlatJacobian J_fd = central_differences(problem, y);
    ASSERT_TRUE(J.allFinite()) << GetParam();
    // relative to the largest entry of the row: the rows of F have their own
    // units (R', v', alpha'). A row that is zero by symmetry (v'_z in the
    // spherical bowl) is compared at 1e-6 of the whole Jacobian instead:
    // central differences leave rounding noise of ~eps |F| / step there
    const double whole = J.cwiseAbs().maxCoeff();
    for (int i = 0; i < kFlatSize; ++i) {
      const double scale = std::max(J.row(i).cwiseAbs().maxCoeff(), 1e-6 * whole);
      const double diff = (J.row(i) - J_fd.row(i)).cwiseAbs().maxCoeff();
      EXPECT_LT(diff, 1e-6 * scale) << GetParam() << " trial " << trial << " row " << i << "\nAD " << J.row(i)
                                    << "\nFD " << J_fd.row(i);
    }
  }
}

TEST_P(JacobianOnScene, ValueIsTheRightHandSide) {
  const Problem problem = make_problem(load_scene(GetParam()));
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const FlatState y = random_state(problem, rng);
    FlatJacobian J;
    FlatState f_ad, f;
    flat_jacobian(problem, y, J, &f_ad);
    problem.flat_rhs(y.data(), f.data());
    // same operations on the values, up to how the compiler contracts them
    EXPECT_LT((f_ad - f).cwiseAbs().maxCoeff(), 1e-14 * std::max(1.0, f.cwiseAbs().maxCoeff())) << GetParam();
  }
}

INSTANTIATE_TEST_SUITE_P(Jacobian, JacobianOnScene,
                         ::testing::Values("valley-sideways", "gaussian-hills", "bowl-3d", "chaplygin-valley"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

// The structure docs/model.md predicts: R' = hat(omega) R is linear in R with
// d(R'_ij)/d(R_kl) = hat(omega)_ik delta_jl, and R never enters (v, alpha)'.
TEST(Jacobian, RotationBlockIsHatOmegaAndRNeverEntersZ) {
  const Problem problem = make_problem(load_scene("valley-sideways"));
  std::mt19937 rng(3);
  const FlatState y = random_state(problem, rng);
  FlatJacobian J;
  flat_jacobian(problem, y, J);
  const RollingBall& m = problem.model();
  const Vec3 omega =
      m.omega_from_momentum(rotation_of(y), m.normal_at(y[kOffsetAlpha], y[kOffsetAlpha + 1]), Vec3(momentum_of(y)));
  const Mat3 W = hat(omega);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) EXPECT_NEAR(J(3 * i + j, 3 * k + l), j == l ? W(i, k) : 0.0, 1e-14);
  const double z_on_R = J.block<kZSize, 9>(kOffsetV, kOffsetR).cwiseAbs().maxCoeff();
  EXPECT_EQ(z_on_R, 0.0);
}

}  // namespace
}  // namespace rb

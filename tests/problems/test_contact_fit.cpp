// The curvature limit (docs/model.md: r max(k1, k2) >= 1 stops a run) is tested
// as "M = I - r II is positive definite" (ModelMargins::ball_fits), with no
// curvature computed. Checked here against closed-form curvatures, and
// against the principal curvatures the derived quantities compute another
// way (from the Hessian, not from C').
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "problems/scene.hpp"

namespace rb {
namespace {

// start: where the ball fits (a scene's start is checked)
Problem scene_with(const std::string& landscape, double radius, double start_x = 0.0) {
  return make_problem(parse_scene(R"js({"name": "fit", "landscape": ")js" + landscape + R"js(",
    "ball": {"radius": )js" + std::to_string(radius) +
                                  R"js(, "mass": 1.0},
    "start": {"contact": [)js" + std::to_string(start_x) +
                                  R"js(, 0.0], "omega": [0, 0, 0]}, "t_end": 1.0})js"));
}

// the start with its contact moved to (x, y) (the margins' curvature part
// does not depend on v or R)
FlatState at(const Problem& p, double x, double y) {
  FlatState s = p.y0();
  s[kOffsetAlpha] = x;
  s[kOffsetAlpha + 1] = y;
  return s;
}

TEST(ContactFit, SphericalBowlHasBothCurvaturesOneOverItsRadius) {
  const double rho = 0.5, r = 0.1;
  const Problem p = scene_with("0.5 - sqrt(0.25 - x^2 - y^2)", r);
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.2, -0.1}, {-0.05, 0.3}}) {
    const Derived d = p.model().derived(at(p, x, y));
    EXPECT_NEAR(d.kappa1, 1.0 / rho, 1e-12) << x << ", " << y;
    EXPECT_NEAR(d.kappa2, 1.0 / rho, 1e-12) << x << ", " << y;
    const ModelMargins m = p.model().margins_at(at(p, x, y));
    EXPECT_NEAR(m.r_kappa_max(), r / rho, 1e-12) << x << ", " << y;
    EXPECT_TRUE(m.ball_fits());
  }
}

// a (x^2 + y^2) at (x, 0): along the radius 2a / (1 + 4a^2 x^2)^(3/2),
// around it 2a / (1 + 4a^2 x^2)^(1/2), the larger
TEST(ContactFit, ParaboloidOffCentreHasItsTwoClosedFormCurvatures) {
  const double a = 6.0, r = 0.1;
  const Problem p = scene_with("6*(x^2 + y^2)", r, 0.3);
  for (const double x : {0.0, 0.05, 0.1, 0.3}) {
    const double s = 1.0 + 4.0 * a * a * x * x;
    const Derived d = p.model().derived(at(p, x, 0.0));
    EXPECT_NEAR(d.kappa1, 2.0 * a / std::sqrt(s), 1e-12) << x;
    EXPECT_NEAR(d.kappa2, 2.0 * a / (s * std::sqrt(s)), 1e-12) << x;
    const ModelMargins m = p.model().margins_at(at(p, x, 0.0));
    EXPECT_NEAR(m.r_kappa_max(), r * 2.0 * a / std::sqrt(s), 1e-12) << x;
    // r kappa_max = 1.2 / sqrt(s) crosses 1 at x = sqrt(0.44) / 12 = 0.0553
    EXPECT_EQ(m.ball_fits(), x > 0.0553) << x;
  }
}

// A saddle's negative curvature never stops a ball: only the larger counts.
TEST(ContactFit, SaddleFitsWhileItsPositiveCurvatureIsBelowOneOverR) {
  const Problem small = scene_with("2*(x^2 - y^2)", 0.2), large = scene_with("2*(x^2 - y^2)", 0.3, 1.0);
  const ModelMargins fits = small.model().margins_at(at(small, 0.0, 0.0));
  EXPECT_NEAR(fits.r_kappa_max(), 0.8, 1e-14);
  EXPECT_TRUE(fits.ball_fits());
  const ModelMargins does_not = large.model().margins_at(at(large, 0.0, 0.0));
  EXPECT_NEAR(does_not.r_kappa_max(), 1.2, 1e-14);
  EXPECT_FALSE(does_not.ball_fits());
}

// Everywhere on a landscape of hills and saddles, for several radii: the
// positive-definite test says what r kappa1 < 1 says (kappa1 from the
// Hessian), away from the limit itself, and r_kappa_max is r kappa1.
TEST(ContactFit, PositiveDefiniteTestAgreesWithTheCurvatureEverywhere) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  int fits = 0, does_not = 0;
  for (const double r : {0.05, 0.2, 0.5, 1.5}) {
    const Problem p = scene_with("0.3*exp(-2*(x^2 + y^2)) + 0.4*sin(2*x)*cos(3*y) + 0.1*x*y", r);
    for (int i = 0; i < 400; ++i) {
      const FlatState s = at(p, u(rng), u(rng));
      const double r_kappa1 = r * p.model().derived(s).kappa1;
      const ModelMargins m = p.model().margins_at(s);
      EXPECT_NEAR(m.r_kappa_max(), r_kappa1, 1e-12 * (1.0 + std::abs(r_kappa1)));
      if (std::abs(r_kappa1 - 1.0) < 1e-9) continue;
      EXPECT_EQ(m.ball_fits(), r_kappa1 < 1.0) << "r = " << r << ", r kappa1 = " << r_kappa1;
      ++(r_kappa1 < 1.0 ? fits : does_not);
    }
  }
  // both sides of the limit were visited
  EXPECT_GT(fits, 200);
  EXPECT_GT(does_not, 200);
}

}  // namespace
}  // namespace rb

#include <gtest/gtest.h>

#include "problems/so3.hpp"

namespace rb {
namespace {

// dexp_u(x) = x + (1 - cos t)/t^2 u x x + (t - sin t)/t^3 u x (u x x)
Vec3 dexp(const Vec3& u, const Vec3& x) {
  const double t = u.norm();
  return x + (1 - std::cos(t)) / (t * t) * u.cross(x) + (t - std::sin(t)) / (t * t * t) * u.cross(u.cross(x));
}

TEST(SO3, ExpMatchesAngleAxisOnBothSidesOfTheSeriesSwitch) {
  for (double t : {1e-9, 1e-4, 9.99e-4, 1.001e-3, 0.1, 1.0, 3.0}) {
    const Vec3 axis = Vec3(1, -2, 0.5).normalized();
    const Mat3 expected = Eigen::AngleAxisd(t, axis).toRotationMatrix();
    EXPECT_LT((so3_exp(t * axis) - expected).norm(), 2e-16 * 8) << t;
  }
}

TEST(SO3, LogInvertsExp) {
  const Vec3 z(0.3, -1.1, 0.7);
  EXPECT_LT((so3_log(so3_exp(z)) - z).norm(), 1e-14);
}

TEST(SO3, DexpinvInvertsDexp) {
  // the closed-form dexp above loses digits for small t, so t >= 5e-3 here
  const Vec3 w(0.4, 0.2, -0.9);
  for (double t : {5e-3, 0.009, 0.011, 0.5, 2.0}) {
    const Vec3 u = t * Vec3(0.6, -0.8, 0.0);
    EXPECT_LT((dexp(u, dexpinv(u, w)) - w).norm(), 1e-14) << t;
  }
}

TEST(SO3, DexpinvSeriesBranchMatchesTheClosedFormAtTheSwitch) {
  // |u|^2 = 1e-4 is where the series takes over: both sides agree there
  const Vec3 w(0.4, 0.2, -0.9);
  const Vec3 dir = Vec3(0.6, -0.8, 0.0);
  for (double t : {0.01 * (1 - 1e-9), 0.01 * (1 + 1e-9)}) {
    // the closed form in long double, where its cancellation costs nothing
    const long double lt = t, c = (1.0L - 0.5L * lt / std::tan(0.5L * lt)) / (lt * lt);
    const Vec3 u = t * dir;
    const Vec3 expected = w - 0.5 * u.cross(w) + static_cast<double>(c) * u.cross(u.cross(w));
    EXPECT_LT((dexpinv(u, w) - expected).norm(), 1e-16) << t;
  }
  // and at tiny angles dexpinv is w - u x w / 2 + u x (u x w) / 12 to rounding
  const Vec3 u = 1e-6 * dir;
  EXPECT_LT((dexpinv(u, w) - (w - 0.5 * u.cross(w) + u.cross(u.cross(w)) / 12.0)).norm(), 1e-17);
}

TEST(SO3, TruncatedSeriesAgreesToFourthOrderAndSeminarDoesNot) {
  const Vec3 w(0.4, 0.2, -0.9);
  const Vec3 dir(0.6, -0.8, 0.3);
  // the truncation error is O(|u|^4); the seminar's sign error O(|u|^2)
  const double e1 = (dexpinv(0.1 * dir, w, DexpinvKind::truncated) - dexpinv(0.1 * dir, w)).norm();
  const double e2 = (dexpinv(0.05 * dir, w, DexpinvKind::truncated) - dexpinv(0.05 * dir, w)).norm();
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, 0.1);
  const double s1 = (dexpinv(0.1 * dir, w, DexpinvKind::seminar) - dexpinv(0.1 * dir, w)).norm();
  const double s2 = (dexpinv(0.05 * dir, w, DexpinvKind::seminar) - dexpinv(0.05 * dir, w)).norm();
  EXPECT_NEAR(std::log2(s1 / s2), 2.0, 0.1);
}

TEST(SO3, ProjectionAndAngle) {
  const Mat3 R = so3_exp(Vec3(0.2, 0.1, -0.3));
  const Mat3 M = 1.001 * R;  // scaled: projection recovers R
  EXPECT_LT((project_to_so3(M) - R).norm(), 1e-14);
  EXPECT_NEAR(rotation_angle_between(R, R * so3_exp(Vec3(0, 1e-9, 0))), 1e-9, 1e-15);
  EXPECT_NEAR(rotation_angle_between(R, R * so3_exp(Vec3(0, 2.0, 0))), 2.0, 1e-14);
  EXPECT_NEAR(rotation_defect(M), std::sqrt(3.0) * (1.001 * 1.001 - 1), 1e-12);
}

}  // namespace
}  // namespace rb

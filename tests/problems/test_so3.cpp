#include <gtest/gtest.h>

#include "problems/so3.hpp"

namespace rb {
namespace {

// dexp_u(x) = x + (1 - cos t)/t^2 u x x + (t - sin t)/t^3 u x (u x x)
Vec3 dexp(const Vec3& u, const Vec3& x) {
  const double t = u.norm();
  return x + (1 - std::cos(t)) / (t * t) * u.cross(x) + (t - std::sin(t)) / (t * t * t) * u.cross(u.cross(x));
}

TEST(SO3, ExpMatchesAngleAxisOnBothSidesOfTheSeriesSwitches) {
  // the short series ends at t = 0.1, the long one at t = 1
  for (double t : {1e-9, 1e-4, 1e-3, 0.0999, 0.1, 0.1001, 0.3, 0.9999, 1.0, 1.0001, 3.0}) {
    const Vec3 axis = Vec3(1, -2, 0.5).normalized();
    const Mat3 expected = Eigen::AngleAxisd(t, axis).toRotationMatrix();
    EXPECT_LT((so3_exp(t * axis) - expected).norm(), 2e-16 * 8) << t;
  }
}

// sin t / t and (1 - cos t) / t^2 in long double, by their closed forms
// (no cancellation to speak of from t = 0.1 on in long double's 64 bits)
void exact_exp_coefficients(long double t, long double& a, long double& b) {
  a = std::sin(t) / t;
  b = (1.0L - std::cos(t)) / (t * t);
}

TEST(SO3, ExpCoefficientsAreExactToRoundingOnTheLongSeries) {
  // from t = 0.1 to 1 the steps' exp takes the series to t^16 instead of
  // sincos: within an ulp or two of the long-double values, and of the
  // closed form's matrix, which the short series (the references') keeps
  for (double t = 0.1; t < 1.0; t += 0.0173) {
    double a = 0.0, b = 0.0;
    so3_exp_coefficients(t * t, a, b);
    long double ea = 0.0L, eb = 0.0L;
    exact_exp_coefficients(t, ea, eb);
    EXPECT_LT(std::abs(a - static_cast<double>(ea)), 2.3e-16 * static_cast<double>(ea)) << t;
    EXPECT_LT(std::abs(b - static_cast<double>(eb)), 2.3e-16 * static_cast<double>(eb)) << t;
    const Vec3 z = t * Vec3(0.3, -0.8, 0.52).normalized();
    EXPECT_LT((so3_exp(z) - so3_exp(z, ExpSeries::below_0_1_rad)).cwiseAbs().maxCoeff(), 4.5e-16) << t;
  }
  // below t = 0.1 both take the same series: the same bits
  const Vec3 small(0.05, -0.03, 0.02);
  EXPECT_EQ(so3_exp(small), so3_exp(small, ExpSeries::below_0_1_rad));
  // from t = 1 on both call sincos: the same bits
  const Vec3 large(0.9, -0.6, 0.4);
  EXPECT_EQ(so3_exp(large), so3_exp(large, ExpSeries::below_0_1_rad));
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

// dexpinv's coefficient (1 - x cot x) / t^2, x = t / 2, in long double and
// without the closed form's cancellation: 1 - x cot x = (sin x - x cos x) /
// sin x, and sin x - x cos x = sum_k>=1 (-1)^(k+1) 2k x^(2k+1) / (2k+1)!
long double exact_dexpinv_coefficient(long double t) {
  const long double x = 0.5L * t;
  long double term = x, sum = 0.0L;  // term = x^(2k+1) / (2k+1)!
  for (int k = 1; k <= 40; ++k) {
    term *= x * x / ((2.0L * k) * (2.0L * k + 1.0L));
    sum += (k % 2 == 1 ? 2.0L : -2.0L) * k * term;
  }
  return sum / std::sin(x) / (t * t);
}

TEST(SO3, DexpinvSeriesBranchMatchesTheClosedFormAtTheSwitch) {
  // |u|^2 = 1e-2 is where the series takes over: both sides agree there
  const Vec3 w(0.4, 0.2, -0.9);
  const Vec3 dir = Vec3(0.6, -0.8, 0.0);
  for (double t : {0.1 * (1 - 1e-9), 0.1 * (1 + 1e-9)}) {
    const long double c = exact_dexpinv_coefficient(t);
    const Vec3 u = t * dir;
    const Vec3 expected = w - 0.5 * u.cross(w) + static_cast<double>(c) * u.cross(u.cross(w));
    EXPECT_LT((dexpinv(u, w) - expected).norm(), 1e-16) << t;
  }
  // and at tiny angles dexpinv is w - u x w / 2 + u x (u x w) / 12 to rounding
  const Vec3 u = 1e-6 * dir;
  EXPECT_LT((dexpinv(u, w) - (w - 0.5 * u.cross(w) + u.cross(u.cross(w)) / 12.0)).norm(), 1e-17);
}

TEST(SO3, DexpinvCoefficientIsExactToRoundingOnBothBranches) {
  // the series below t = 1 (to t^8 below 0.1, to t^18 from there), the
  // closed form above: within 2 ulp of the long-double value everywhere up
  // to the pole guard, NaN from there on
  for (double t = 1e-4; t < kDexpinvMaxAngle; t *= 1.1) {
    const double c = dexpinv_coefficient(t * t);
    const double exact = static_cast<double>(exact_dexpinv_coefficient(t));
    // the closed form's cancellation costs up to ~12 eps / t^2 relative
    const double allowed = t < 1.0 ? 4.5e-16 : 4.5e-16 + 4e-15 / (t * t);
    EXPECT_LT(std::abs(c - exact), allowed * exact) << t;
  }
  EXPECT_TRUE(std::isnan(dexpinv_coefficient(kDexpinvMaxAngle * kDexpinvMaxAngle)));
  EXPECT_TRUE(std::isnan(dexpinv_coefficient(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_DOUBLE_EQ(dexpinv_coefficient(0.0), 1.0 / 12.0);
  // and on both sides of the long series' end at t = 1
  for (double t : {1.0 - 1e-9, 1.0, 1.0 + 1e-9}) {
    const double exact = static_cast<double>(exact_dexpinv_coefficient(t));
    EXPECT_LT(std::abs(dexpinv_coefficient(t * t) - exact), 4.5e-15 * exact) << t;
  }
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

#pragma once
// The rotation group SO(3) and its Lie algebra so(3) ~ R^3: hat, exp by
// Rodrigues' formula, log, and the inverse of the exponential's derivative
// (dexpinv) used by Runge-Kutta-Munthe-Kaas methods (docs/model.md, "The methods compared").
#include <cmath>
#include <limits>

#include "problems/state.hpp"

namespace rb {

// hat(w) x = w x x.
inline Mat3 hat(const Vec3& w) {
  Mat3 W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

// Which angles exp's Taylor polynomials cover (the rest calls sincos):
// t < 0.1 only, as every exp did until 2026-12-05 (the closed-form
// references of problems/exact.cpp keep their bits so), or t < 1 (the steps:
// an adaptive step of the Chaplygin scenes turns the ball by 0.1-0.3 rad).
enum class ExpSeries { below_0_1_rad, below_1_rad };

// a = sin t / t and b = (1 - cos t) / t^2 at t^2 = |z|^2 (exp's and its
// derivative's coefficients). Below t^2 = 1e-2 (t < 0.1 rad) the Taylor
// series to t^8 (truncation below 3e-18 relative); from there to t^2 = 1
// (series = below_1_rad) to t^16 (truncation below 1e-17 relative: t^18 /
// 19! < 8.3e-18 and t^18 / 20! < 4.2e-19, under half an ulp of a >= sin 1
// and b >= 1 - cos 1): no sincos, square root or division, and no
// cancellation in 1 - cos t. The same numbers to rounding either way.
[[gnu::always_inline]] inline void so3_exp_coefficients(double t2, double& a, double& b,
                                                        ExpSeries series = ExpSeries::below_1_rad) {
  if (t2 < 1e-2) [[likely]] {
    a = 1.0 + t2 * (-1.0 / 6.0 + t2 * (1.0 / 120.0 + t2 * (-1.0 / 5040.0 + t2 * (1.0 / 362880.0))));
    b = 0.5 + t2 * (-1.0 / 24.0 + t2 * (1.0 / 720.0 + t2 * (-1.0 / 40320.0 + t2 * (1.0 / 3628800.0))));
  } else if (series == ExpSeries::below_1_rad && t2 < 1.0) {
    a = 1.0 + t2 * (-1.0 / 6.0 +
                    t2 * (1.0 / 120.0 +
                          t2 * (-1.0 / 5040.0 +
                                t2 * (1.0 / 362880.0 +
                                      t2 * (-1.0 / 39916800.0 +
                                            t2 * (1.0 / 6227020800.0 +
                                                  t2 * (-1.0 / 1307674368000.0 + t2 * (1.0 / 355687428096000.0))))))));
    b = 0.5 + t2 * (-1.0 / 24.0 +
                    t2 * (1.0 / 720.0 +
                          t2 * (-1.0 / 40320.0 +
                                t2 * (1.0 / 3628800.0 +
                                      t2 * (-1.0 / 479001600.0 +
                                            t2 * (1.0 / 87178291200.0 + t2 * (-1.0 / 20922789888000.0 +
                                                                              t2 * (1.0 / 6402373705728000.0))))))));
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
}

// exp(hat(z)) = I + a hat(z) + b hat(z)^2 (so3_exp_coefficients), written
// entry by entry with hat(z)^2 = z z^T - t^2 I: no 3x3 product (callgrind:
// 160 -> 78 instructions a call), the same matrix to rounding.
// Always inlined: the stage loops that form exp(U) R_n called it out of line.
[[gnu::always_inline]] inline Mat3 so3_exp(const Vec3& z, ExpSeries series = ExpSeries::below_1_rad) {
  const double x = z.x(), y = z.y(), w = z.z();
  const double xx = x * x, yy = y * y, ww = w * w;
  double a, b;
  so3_exp_coefficients(xx + yy + ww, a, b, series);
  const double bxy = b * x * y, bxw = b * x * w, byw = b * y * w;
  const double ax = a * x, ay = a * y, aw = a * w;
  Mat3 E;
  E(0, 0) = 1.0 - b * (yy + ww), E(0, 1) = bxy - aw, E(0, 2) = bxw + ay;
  E(1, 0) = bxy + aw, E(1, 1) = 1.0 - b * (xx + ww), E(1, 2) = byw - ax;
  E(2, 0) = bxw - ay, E(2, 1) = byw + ax, E(2, 2) = 1.0 - b * (xx + yy);
  return E;
}

// The rotation vector of R (angle in [0, pi]), for error measurement.
inline Vec3 so3_log(const Mat3& R) {
  Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

// Rotation angle of R_a^T R_b after projecting both onto SO(3).
double rotation_angle_between(const Mat3& R_a, const Mat3& R_b);

// The closest rotation to M (polar decomposition through the SVD).
Mat3 project_to_so3(const Mat3& M);

// ||R^T R - I||_F: how far R has drifted off SO(3).
inline double rotation_defect(const Mat3& R) { return (R.transpose() * R - Mat3::Identity()).norm(); }

// The closest rotation to M, as project_to_so3, for M near SO(3) (a step's
// R): Newton-Schulz (Bjorck-Bowie) steps X <- X (I - E / 2), E = X^T X - I,
// which square the defect, so one step suffices once max |E_ij| < 1e-8
// (the defect left is then below rounding). M far from SO(3) (max |E_ij|
// >= 1/2, where the iteration may not converge) or with det M < 0 (whose
// polar factor is no rotation) goes to the SVD.
inline Mat3 project_to_so3_newton_schulz(const Mat3& M) {
  if (!(M.determinant() > 0.0)) return project_to_so3(M);
  Mat3 X = M;
  for (int i = 0; i < 8; ++i) {
    const Mat3 E = X.transpose() * X - Mat3::Identity();
    const double defect = E.cwiseAbs().maxCoeff();
    if (!(defect < 0.5)) return project_to_so3(M);
    X -= 0.5 * (X * E);
    if (defect < 1e-8) break;
  }
  return X;
}

// Which formula dexpinv uses.
enum class DexpinvKind {
  exact,      // closed form for so(3)
  truncated,  // w - u x w / 2 + u x (u x w) / 12: enough for order 4
  seminar,    // the seminar's sign error: w - u x w / 2 - u x (u x w) / 12
};

// The largest |u| the closed-form dexpinv takes: its coefficient grows
// without bound towards the pole at |u| = 2 pi (where exp is not locally
// invertible), and is 0.46 here; a step that turns the ball this far
// (15/16 of a turn) has no accuracy left.
inline constexpr double kDexpinvMaxAngle = 2.0 * M_PI * (15.0 / 16.0);

// The coefficient of u x (u x w) in the closed-form dexpinv at t^2 = |u|^2:
// (1 - (t/2) cot(t/2)) / t^2 = sum_n |B_2n| t^(2n-2) / (2n)!, each term
// about t^2 / (2 pi)^2 of the one before. Below t^2 = 1e-2 the series to
// t^8 (truncation below 1e-19 relative; the closed form loses up to 1e-11
// relative there to cancellation); from there to t^2 = 1 to t^18 (truncation
// below 7e-17 relative), so that no step of a converged run, nor an adaptive
// step that turns the ball by up to 1 rad, calls tan. The same number to
// rounding as the closed form. NaN from kDexpinvMaxAngle on. The short
// series is inlined into the stages, the rest (dexpinv_coefficient_wide)
// called: out of line as a whole it cost a call a stage.
double dexpinv_coefficient_wide(double t2);  // so3.cpp
[[gnu::always_inline]] inline double dexpinv_coefficient(double t2) {
  if (t2 < 1e-2) [[likely]]
    return 1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 * (1.0 / 1209600.0 + t2 * (1.0 / 47900160.0))));
  return dexpinv_coefficient_wide(t2);
}

// |u|^2 as x^2 + y^2 + z^2, summed in that order: dexpinv's t^2, and the
// RKMK stages' chart-edge test (rkmk_stepper.hpp), which is written with it
// so that a stage forms it once.
[[gnu::always_inline]] inline double squared_angle(const Vec3& u) {
  return u.x() * u.x() + u.y() * u.y() + u.z() * u.z();
}

// dexpinv_u(w) = w - 1/2 u x w + (1/t^2)(1 - (t/2) cot(t/2)) u x (u x w),
// t = |u| (dexpinv_coefficient). For |u| >= kDexpinvMaxAngle the exact form
// is NaN, never a wrong number: a fixed-step RKMK run ends "chart-limit" at
// the last valid state (rkmk_stepper.hpp), an adaptive step is rejected and
// shrunk. Inlined into the
// stage loops, where kind is known for the whole run.
[[gnu::always_inline]] inline Vec3 dexpinv(const Vec3& u, const Vec3& w, DexpinvKind kind = DexpinvKind::exact) {
  const double u0 = u.x(), u1 = u.y(), u2 = u.z();
  const double uw0 = u1 * w.z() - u2 * w.y(), uw1 = u2 * w.x() - u0 * w.z(), uw2 = u0 * w.y() - u1 * w.x();
  const double uuw0 = u1 * uw2 - u2 * uw1, uuw1 = u2 * uw0 - u0 * uw2, uuw2 = u0 * uw1 - u1 * uw0;
  const double c = kind == DexpinvKind::exact       ? dexpinv_coefficient(squared_angle(u))
                   : kind == DexpinvKind::truncated ? 1.0 / 12.0
                                                    : -1.0 / 12.0;
  return {w.x() - 0.5 * uw0 + c * uuw0, w.y() - 0.5 * uw1 + c * uuw1, w.z() - 0.5 * uw2 + c * uuw2};
}

}  // namespace rb

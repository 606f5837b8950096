#pragma once
// The rotation group SO(3) and its Lie algebra so(3) ~ R^3: hat, exp by
// Rodrigues' formula, log, and the inverse of the exponential's derivative
// (dexpinv) used by Runge-Kutta-Munthe-Kaas methods (MODEL.md, family 3).
#include <cmath>
#include <limits>

#include "problems/state.hpp"

namespace rb {

// hat(w) x = w x x.
inline Mat3 hat(const Vec3& w) {
  Mat3 W;
  W << 0, -w.z(), w.y(),
       w.z(), 0, -w.x(),
       -w.y(), w.x(), 0;
  return W;
}

// exp(hat(z)) = I + (sin t / t) hat(z) + ((1 - cos t) / t^2) hat(z)^2, t = |z|.
// Below t^2 = 1e-2 (t < 0.1 rad, every step of a converged run) the Taylor
// series to t^8 is used: its truncation error is below 3e-18 relative, under
// rounding, and it avoids the sincos call, the square root and the division
// (about a tenth of an RKMK4 step), as well as the cancellation in 1 - cos t.
inline Mat3 so3_exp(const Vec3& z) {
  const double t2 = z.squaredNorm();
  double a, b;
  if (t2 < 1e-2) {
    a = 1.0 + t2 * (-1.0 / 6.0 + t2 * (1.0 / 120.0 + t2 * (-1.0 / 5040.0 + t2 * (1.0 / 362880.0))));
    b = 0.5 + t2 * (-1.0 / 24.0 + t2 * (1.0 / 720.0 + t2 * (-1.0 / 40320.0 + t2 * (1.0 / 3628800.0))));
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
  const Mat3 Z = hat(z);
  return Mat3::Identity() + a * Z + b * Z * Z;
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
inline double rotation_defect(const Mat3& R) {
  return (R.transpose() * R - Mat3::Identity()).norm();
}

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

// dexpinv_u(w) = w - 1/2 u x w + (1/t^2)(1 - (t/2) cot(t/2)) u x (u x w),
// t = |u|; near t = 0 the coefficient is 1/12 + t^2/720 + t^4/30240. For
// |u| >= kDexpinvMaxAngle the exact form is NaN, never a wrong number: a
// fixed-step run ends "diverged" at the last valid state, an adaptive
// step is rejected and shrunk.
inline Vec3 dexpinv(const Vec3& u, const Vec3& w, DexpinvKind kind = DexpinvKind::exact) {
  const Vec3 uw = u.cross(w);
  const Vec3 uuw = u.cross(uw);
  double c;
  switch (kind) {
    case DexpinvKind::truncated: c = 1.0 / 12.0; break;
    case DexpinvKind::seminar: c = -1.0 / 12.0; break;
    case DexpinvKind::exact:
    default: {
      const double t2 = u.squaredNorm();
      if (t2 < 1e-4) {
        c = 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0;
      } else if (!(t2 < kDexpinvMaxAngle * kDexpinvMaxAngle)) {
        return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
      } else {
        const double t = std::sqrt(t2);
        c = (1.0 - 0.5 * t / std::tan(0.5 * t)) / t2;
      }
    }
  }
  return w - 0.5 * uw + c * uuw;
}

}  // namespace rb

#include "problems/rolling_ball.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

#include "problems/so3.hpp"

namespace rb {

namespace {

// The principal curvatures (k1 >= k2, > 0 where concave) of z = f(x, y):
// the eigenvalues of I^-1 II, first fundamental form I = [[1 + fx^2, fx fy],
// [fx fy, 1 + fy^2]], second II = Hess f / w, w = sqrt(1 + fx^2 + fy^2).
std::pair<double, double> principal_curvatures(const Jet2<double>& f) {
  const double w2 = 1.0 + f.fx * f.fx + f.fy * f.fy, w = std::sqrt(w2);
  const double E1 = 1.0 + f.fx * f.fx, F1 = f.fx * f.fy, G1 = 1.0 + f.fy * f.fy;
  const double gauss = (f.fxx * f.fyy - f.fxy * f.fxy) / (w2 * w2);
  const double mean = 0.5 * (f.fxx * G1 - 2.0 * f.fxy * F1 + f.fyy * E1) / (w2 * w);
  const double disc = std::sqrt(std::max(0.0, mean * mean - gauss));
  return {mean + disc, mean - disc};
}

}  // namespace

double ModelMargins::r_kappa_max() const {
  // the eigenvalues mu of I^-1 M solve det(M - mu I) = 0, i.e.
  // det(I) mu^2 - b mu + det(M) = 0, and r kappa = 1 - mu
  const double I_xx = 1.0 + slope_x * slope_x, I_xy = slope_x * slope_y, I_yy = 1.0 + slope_y * slope_y;
  const double a = I_xx * I_yy - I_xy * I_xy;
  const double b = fit_xx * I_yy + fit_yy * I_xx - 2.0 * fit_xy * I_xy;
  const double c = fit_xx * fit_yy - fit_xy * fit_xy;
  const double mu_min = (b - std::sqrt(std::max(0.0, b * b - 4.0 * a * c))) / (2.0 * a);
  return 1.0 - mu_min;
}

RollingBall::RollingBall(Landscape landscape, BallParams params) : landscape_(std::move(landscape)), p_(params) {
  const double mr2 = p_.mass * p_.radius * p_.radius;
  mr2_ = mr2;
  mrg_ = p_.mass * p_.radius * p_.gravity;
  const Vec3* I = p_.inertia ? &*p_.inertia : nullptr;
  general_ = I != nullptr;
  anisotropic_ = I && !((*I)[0] == (*I)[1] && (*I)[1] == (*I)[2]);
  if (anisotropic_) {
    inv_d_ = (I->array() + mr2).inverse().matrix();
  } else if (I) {
    theta_ = (*I)[0];
    iso_scale_ = 1.0 / (theta_ + mr2);
    iso_normal_ = mr2 / theta_;
  } else {
    // the homogeneous ball's constants as they always were
    theta_ = 0.4 * mr2;
    iso_scale_ = (5.0 / 7.0) / mr2;
    iso_normal_ = 2.5;
  }
}

Vec3 RollingBall::normal_at(double x, double y) const {
  const Jet2<double> f = landscape_.at(x, y);
  return Vec3(-f.fx, -f.fy, 1.0).normalized();
}

ModelMargins RollingBall::margins_at(const FlatState& y) const {
  return margins_of(kinematics(RowMajorRotation<double>{y.data() + kOffsetR}, y.data() + kOffsetV));
}

Mat3 RollingBall::contact_inertia(const Mat3& R, const Vec3& N) const {
  const double mr2 = p_.mass * p_.radius * p_.radius;
  const Mat3 about_centre =
      anisotropic_ ? Mat3(R * p_.inertia->asDiagonal() * R.transpose()) : Mat3(theta_ * Mat3::Identity());
  return about_centre + mr2 * (Mat3::Identity() - N * N.transpose());
}

Vec3 RollingBall::omega_from_momentum(const Mat3& R, const Vec3& N, const Vec3& v) const {
  // equal moments: T^-1 = s (I + c N N^T), as in kinematics
  if (!anisotropic_) return (v + iso_normal_ * N * N.dot(v)) * iso_scale_;
  const double n[3] = {N.x(), N.y(), N.z()};
  double w[3];
  anisotropic_omega(R, n, v.data(), w);
  return {w[0], w[1], w[2]};
}

Vec3 RollingBall::momentum_from_omega(const Mat3& R, const Vec3& N, const Vec3& omega) const {
  const double mr2 = p_.mass * p_.radius * p_.radius;
  // the homogeneous ball's T omega = m r^2 (7/5 omega - N (N . omega)), as it always was
  if (!p_.inertia) return mr2 * (1.4 * omega - N * N.dot(omega));
  return contact_inertia(R, N) * omega;
}

Derived RollingBall::derived(const FlatState& y) const {
  const double r = p_.radius, m = p_.mass, g0 = p_.gravity;
  const Mat3 R = rotation_of(y);
  const Kinematics<double> k = kinematics(R, y.data() + kOffsetV);
  const Vec3 v = momentum_of(y);
  const Vec2 alpha = contact_of(y);
  Derived d;
  d.N = k.N;
  d.omega = k.omega;
  d.centre = Vec3(alpha.x(), alpha.y(), landscape_.height(alpha.x(), alpha.y())) + r * k.N;
  d.centre_velocity = r * k.omega.cross(k.N);
  d.energy = 0.5 * k.omega.dot(v) + m * g0 * d.centre.z();
  d.spin = k.omega.dot(k.N);
  d.det_E = k.det_E;

  // contact force F = m c'' - m g with c'' = r (omega' x N + omega x N_dot),
  // omega' = T^-1 (v' - T' omega), T' omega = -m r^2 (N_dot (N.omega) + N (N_dot.omega))
  // plus, for the anisotropic ball, the gyroscopic d/dt(R Theta R^T) omega = omega x (R Theta R^T omega)
  const Vec3 N_dot = k.N_d * k.alpha_dot;
  Vec3 T_d_omega = -m * r * r * (N_dot * k.N.dot(k.omega) + k.N * N_dot.dot(k.omega));
  if (anisotropic_) T_d_omega += k.omega.cross(R * p_.inertia->asDiagonal() * R.transpose() * k.omega);
  const Vec3 omega_dot = omega_from_momentum(R, k.N, Vec3(k.v_dot - T_d_omega));
  const Vec3 c_dd = r * (omega_dot.cross(k.N) + k.omega.cross(N_dot));
  const Vec3 F = m * c_dd + Vec3(0.0, 0.0, m * g0);
  d.normal_force = F.dot(k.N);

  std::tie(d.kappa1, d.kappa2) = principal_curvatures(k.f);

  d.rotation_defect = rb::rotation_defect(R);
  d.det_defect = R.determinant() - 1.0;
  return d;
}

}  // namespace rb

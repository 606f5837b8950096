#include "problems/rolling_ball.hpp"

#include "problems/so3.hpp"

namespace rb {

Vec3 RollingBall::normal_at(double x, double y) const {
  const Jet2<double> f = landscape_.at(x, y);
  return Vec3(-f.fx, -f.fy, 1.0).normalized();
}

Derived RollingBall::derived(const FlatState& y) const {
  const double r = p_.radius, m = p_.mass, g0 = p_.gravity;
  const Kinematics<double> k = kinematics(y.data() + kOffsetV);
  const Jet2<double>& f = k.f;
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
  const Vec3 N_dot = k.N_d * k.alpha_dot;
  const Vec3 T_d_omega = -m * r * r * (N_dot * k.N.dot(k.omega) + k.N * N_dot.dot(k.omega));
  const Vec3 omega_dot = omega_from_momentum(k.N, Vec3(k.v_dot - T_d_omega));
  const Vec3 c_dd = r * (omega_dot.cross(k.N) + k.omega.cross(N_dot));
  const Vec3 F = m * c_dd + Vec3(0.0, 0.0, m * g0);
  d.normal_force = F.dot(k.N);

  // principal curvatures: eigenvalues of I^-1 II, first fundamental form
  // I = [[1 + fx^2, fx fy], [fx fy, 1 + fy^2]], second II = Hess f / w
  const double w2 = 1.0 + f.fx * f.fx + f.fy * f.fy;
  const double w = std::sqrt(w2);
  const double e = f.fxx / w, fm = f.fxy / w, g = f.fyy / w;
  const double E1 = 1.0 + f.fx * f.fx, F1 = f.fx * f.fy, G1 = 1.0 + f.fy * f.fy;
  const double gauss = (e * g - fm * fm) / w2;
  const double mean = 0.5 * (e * G1 - 2.0 * fm * F1 + g * E1) / w2;
  const double disc = std::sqrt(std::max(0.0, mean * mean - gauss));
  d.kappa1 = mean + disc;
  d.kappa2 = mean - disc;

  const Mat3 R = rotation_of(y);
  d.rotation_defect = rb::rotation_defect(R);
  d.det_defect = R.determinant() - 1.0;
  return d;
}

}  // namespace rb

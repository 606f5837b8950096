#pragma once
// The rolling-ball ODE of MODEL.md: a homogeneous ball of radius r and mass m
// rolling without slipping on z = f(x, y) under gravity (0, 0, -g0).
//
// The right-hand side is a template over the scalar type T so that it runs on
// doubles in the step loop and on forward-mode AD numbers for the exact
// Jacobian. Nothing here allocates.
#include <cmath>

#include "problems/landscape.hpp"
#include "problems/state.hpp"

namespace rb {

struct BallParams {
  double radius = 0.1;  // r > 0
  double mass = 1.0;    // m > 0
  double gravity = 9.81;  // g0: gravity is (0, 0, -g0)
};

// Everything the equations of motion need at one state (v, alpha), in the
// world frame. Shapes: N 3, N' 3x2, C' 3x2, E 2x2.
template <class T>
struct Kinematics {
  using V2 = Eigen::Matrix<T, 2, 1>;
  using V3 = Eigen::Matrix<T, 3, 1>;
  V3 N;                           // upward unit normal
  Eigen::Matrix<T, 3, 2> N_d;     // N' = dN / d(x, y)
  Eigen::Matrix<T, 3, 2> C_d;     // C' = phi' + r N'
  Eigen::Matrix<T, 2, 2> E;       // C'^T C'
  T det_E;
  V3 omega;                       // angular velocity, world frame
  V2 alpha_dot;                   // contact point velocity
  V3 v_dot;                       // rate of the angular momentum about the contact
  Jet2<T> f;                      // landscape value, gradient, Hessian
};

// Derived quantities at one flat state (MODEL.md, "Derived quantities").
struct Derived {
  Vec3 N;                // upward unit normal at the contact
  Vec3 centre;           // c = phi + r N
  Vec3 centre_velocity;  // c' = r omega x N
  Vec3 omega;            // world frame
  double energy;         // H = 1/2 omega^T T omega + m g0 c_z
  double spin;           // s = omega . N
  double normal_force;   // F . N, F = m c'' - m g
  double kappa1, kappa2; // principal curvatures, kappa1 >= kappa2, > 0 concave
  double det_E;          // det(C'^T C'): 0 where the contact is singular
  double rotation_defect;  // ||R^T R - I||_F
  double det_defect;       // det R - 1
};

class RollingBall {
 public:
  RollingBall(Landscape landscape, BallParams params)
      : landscape_(std::move(landscape)), p_(params) {}

  const Landscape& landscape() const { return landscape_; }
  const BallParams& params() const { return p_; }

  // The equations of motion at z = (v, alpha).
  template <class T>
  Kinematics<T> kinematics(const T* z) const;

  // Lie-group view: omega(z) and G(z) = (v', alpha') in one pass.
  // z and dz hold kZSize numbers; omega 3.
  template <class T>
  void lie_rhs(const T* z, T* omega, T* dz) const {
    const Kinematics<T> k = kinematics(z);
    for (int i = 0; i < 3; ++i) omega[i] = k.omega[i];
    for (int i = 0; i < 3; ++i) dz[i] = k.v_dot[i];
    dz[3] = k.alpha_dot[0];
    dz[4] = k.alpha_dot[1];
  }

  // Flat view: y' = F(y) for y in R^14 (R row-major, v, alpha); R' = hat(omega) R.
  template <class T>
  void flat_rhs(const T* y, T* dy) const {
    const Kinematics<T> k = kinematics(y + kOffsetV);
    const T* R = y + kOffsetR;
    T* dR = dy + kOffsetR;
    const Eigen::Matrix<T, 3, 1>& w = k.omega;
    // (hat(w) R) column by column: w x (column j of R)
    for (int j = 0; j < 3; ++j) {
      const T r0 = R[0 * 3 + j], r1 = R[1 * 3 + j], r2 = R[2 * 3 + j];
      dR[0 * 3 + j] = w[1] * r2 - w[2] * r1;
      dR[1 * 3 + j] = w[2] * r0 - w[0] * r2;
      dR[2 * 3 + j] = w[0] * r1 - w[1] * r0;
    }
    for (int i = 0; i < 3; ++i) dy[kOffsetV + i] = k.v_dot[i];
    dy[kOffsetAlpha] = k.alpha_dot[0];
    dy[kOffsetAlpha + 1] = k.alpha_dot[1];
  }

  // T^-1 v = (5/7) / (m r^2) (v + (5/2) N (N . v)): angular velocity from
  // the angular momentum about the contact point.
  template <class T>
  Eigen::Matrix<T, 3, 1> omega_from_momentum(const Eigen::Matrix<T, 3, 1>& N,
                                             const Eigen::Matrix<T, 3, 1>& v) const {
    const double s = (5.0 / 7.0) / (p_.mass * p_.radius * p_.radius);
    return (v + 2.5 * N * N.dot(v)) * s;
  }
  // T omega = m r^2 (7/5 omega - N (N . omega)).
  Vec3 momentum_from_omega(const Vec3& N, const Vec3& omega) const {
    return p_.mass * p_.radius * p_.radius * (1.4 * omega - N * N.dot(omega));
  }

  // The upward unit normal at the contact point (x, y).
  Vec3 normal_at(double x, double y) const;

  // Every derived quantity of MODEL.md at a flat state.
  Derived derived(const FlatState& y) const;

 private:
  Landscape landscape_;
  BallParams p_;
};

template <class T>
Kinematics<T> RollingBall::kinematics(const T* z) const {
  using std::sqrt;
  using V3 = Eigen::Matrix<T, 3, 1>;
  Kinematics<T> k;
  const double r = p_.radius, m = p_.mass;
  const V3 v(z[0], z[1], z[2]);
  k.f = landscape_.at(z[3], z[4]);
  const Jet2<T>& f = k.f;

  // N = (-fx, -fy, 1) / w and its Jacobian N' = (I - N N^T) n' / w
  const T w2 = T(1.0) + f.fx * f.fx + f.fy * f.fy;
  const T w = sqrt(w2);
  const T inv_w = T(1.0) / w;
  k.N = V3(-f.fx * inv_w, -f.fy * inv_w, inv_w);
  const V3 dn_x(-f.fxx, -f.fxy, T(0.0));
  const V3 dn_y(-f.fxy, -f.fyy, T(0.0));
  k.N_d.col(0) = (dn_x - k.N * k.N.dot(dn_x)) * inv_w;
  k.N_d.col(1) = (dn_y - k.N * k.N.dot(dn_y)) * inv_w;

  // C' = phi' + r N', phi' = [[1, 0], [0, 1], [fx, fy]]
  k.C_d = r * k.N_d;
  k.C_d(0, 0) += T(1.0);
  k.C_d(1, 1) += T(1.0);
  k.C_d(2, 0) += f.fx;
  k.C_d(2, 1) += f.fy;
  k.E = k.C_d.transpose() * k.C_d;
  k.det_E = k.E(0, 0) * k.E(1, 1) - k.E(0, 1) * k.E(1, 0);

  k.omega = omega_from_momentum(k.N, v);

  // alpha' = r E^-1 C'^T (omega x N), with the 2x2 inverse written out
  const V3 wxN = k.omega.cross(k.N);
  const Eigen::Matrix<T, 2, 1> b = k.C_d.transpose() * wxN;
  const T inv_det = T(r) / k.det_E;
  k.alpha_dot[0] = (k.E(1, 1) * b[0] - k.E(0, 1) * b[1]) * inv_det;
  k.alpha_dot[1] = (k.E(0, 0) * b[1] - k.E(1, 0) * b[0]) * inv_det;

  // v' = m r (N x g) - m r^2 (N' alpha') x (N x omega), g = (0, 0, -g0)
  const V3 N_dot = k.N_d * k.alpha_dot;
  const T g0 = T(p_.gravity);
  const V3 Nxg(-k.N[1] * g0, k.N[0] * g0, T(0.0));
  k.v_dot = (m * r) * Nxg - (m * r * r) * N_dot.cross(k.N.cross(k.omega));
  return k;
}

}  // namespace rb

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
  Jet2<T> f;                      // landscape gradient and Hessian; f.f is NaN (not needed)
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

  // The equations of motion at z = (v, alpha). Always inlined, so that in
  // lie_rhs and flat_rhs the parts they do not return are never stored.
  template <class T>
  [[gnu::always_inline]] inline Kinematics<T> kinematics(const T* z) const;

  // Lie-group view: omega(z) and G(z) = (v', alpha') in one pass.
  // z and dz hold kZSize numbers; omega 3.
  template <class T>
  [[gnu::always_inline]] void lie_rhs(const T* z, T* omega, T* dz) const {
    const Kinematics<T> k = kinematics(z);
    for (int i = 0; i < 3; ++i) omega[i] = k.omega[i];
    for (int i = 0; i < 3; ++i) dz[i] = k.v_dot[i];
    dz[3] = k.alpha_dot[0];
    dz[4] = k.alpha_dot[1];
  }

  // Flat view: y' = F(y) for y in R^14 (R row-major, v, alpha); R' = hat(omega) R.
  template <class T>
  [[gnu::always_inline]] void flat_rhs(const T* y, T* dy) const {
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

// Written out in scalars rather than with Eigen's 3-vectors: this is the hot
// path of every integrator, and scalar code lets the compiler keep the whole
// state in registers (Eigen's fixed-size temporaries cost about a third more
// per evaluation here).
template <class T>
Kinematics<T> RollingBall::kinematics(const T* z) const {
  using std::sqrt;
  Kinematics<T> k;
  const double r = p_.radius, m = p_.mass;
  k.f = landscape_.slopes(z[3], z[4]);
  const Jet2<T>& f = k.f;

  // N = (-fx, -fy, 1) / w and its Jacobian N' = (I - N N^T) n' / w, where
  // the columns of n' are (-fxx, -fxy, 0) and (-fxy, -fyy, 0)
  const T inv_w = T(1.0) / sqrt(T(1.0) + f.fx * f.fx + f.fy * f.fy);
  const T N0 = -f.fx * inv_w, N1 = -f.fy * inv_w, N2 = inv_w;
  const T px = -(N0 * f.fxx + N1 * f.fxy), py = -(N0 * f.fxy + N1 * f.fyy);  // N . n'
  const T Nx0 = (-f.fxx - N0 * px) * inv_w, Nx1 = (-f.fxy - N1 * px) * inv_w, Nx2 = -(N2 * px) * inv_w;
  const T Ny0 = (-f.fxy - N0 * py) * inv_w, Ny1 = (-f.fyy - N1 * py) * inv_w, Ny2 = -(N2 * py) * inv_w;

  // C' = phi' + r N', phi' = [[1, 0], [0, 1], [fx, fy]]; E = C'^T C'
  const T Cx0 = r * Nx0 + 1.0, Cx1 = r * Nx1, Cx2 = r * Nx2 + f.fx;
  const T Cy0 = r * Ny0, Cy1 = r * Ny1 + 1.0, Cy2 = r * Ny2 + f.fy;
  const T E00 = Cx0 * Cx0 + Cx1 * Cx1 + Cx2 * Cx2;
  const T E01 = Cx0 * Cy0 + Cx1 * Cy1 + Cx2 * Cy2;
  const T E11 = Cy0 * Cy0 + Cy1 * Cy1 + Cy2 * Cy2;
  const T det_E = E00 * E11 - E01 * E01;

  // omega = T^-1 v = (5/7) / (m r^2) (v + (5/2) N (N . v))
  const double s = (5.0 / 7.0) / (m * r * r);
  const T Nv = 2.5 * (N0 * z[0] + N1 * z[1] + N2 * z[2]);
  const T w0 = (z[0] + N0 * Nv) * s, w1 = (z[1] + N1 * Nv) * s, w2 = (z[2] + N2 * Nv) * s;

  // alpha' = r E^-1 C'^T (omega x N), with the 2x2 inverse written out
  const T q0 = w1 * N2 - w2 * N1, q1 = w2 * N0 - w0 * N2, q2 = w0 * N1 - w1 * N0;
  const T b0 = Cx0 * q0 + Cx1 * q1 + Cx2 * q2, b1 = Cy0 * q0 + Cy1 * q1 + Cy2 * q2;
  const T inv_det = r / det_E;
  const T ax = (E11 * b0 - E01 * b1) * inv_det, ay = (E00 * b1 - E01 * b0) * inv_det;

  // v' = m r (N x g) - m r^2 (N' alpha') x (N x omega), g = (0, 0, -g0);
  // N x omega = -(omega x N) = -q
  const T d0 = Nx0 * ax + Ny0 * ay, d1 = Nx1 * ax + Ny1 * ay, d2 = Nx2 * ax + Ny2 * ay;  // N' alpha'
  const double mrg = m * r * p_.gravity, mr2 = m * r * r;

  k.N = {N0, N1, N2};
  k.N_d << Nx0, Ny0, Nx1, Ny1, Nx2, Ny2;
  k.C_d << Cx0, Cy0, Cx1, Cy1, Cx2, Cy2;
  k.E << E00, E01, E01, E11;
  k.det_E = det_E;
  k.omega = {w0, w1, w2};
  k.alpha_dot = {ax, ay};
  k.v_dot = {-mrg * N1 + mr2 * (d1 * q2 - d2 * q1), mrg * N0 + mr2 * (d2 * q0 - d0 * q2),
             mr2 * (d0 * q1 - d1 * q0)};
  return k;
}

}  // namespace rb

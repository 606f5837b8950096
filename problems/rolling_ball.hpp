#pragma once
// The rolling-ball ODE of docs/model.md: a ball of radius r and mass m rolling
// without slipping on z = f(x, y) under gravity (0, 0, -g0). The ball is
// homogeneous unless its principal moments are given (a Chaplygin ball,
// "A ball whose orientation matters"): then R enters T(R, alpha).
//
// The right-hand side is a template over the scalar type T so that it runs on
// doubles in the step loop and on forward-mode AD numbers for the exact
// Jacobian. Nothing here allocates.
#include <cmath>
#include <limits>
#include <optional>

#include "problems/landscape.hpp"
#include "problems/state.hpp"

namespace rb {

struct BallParams {
  double radius = 0.1;    // r > 0
  double mass = 1.0;      // m > 0
  double gravity = 9.81;  // g0: gravity is (0, 0, -g0)
  // Principal moments (I1, I2, I3) about the body axes; absent: the
  // homogeneous ball, (2/5) m r^2 each, and R does not enter the motion.
  std::optional<Vec3> inertia;
};

// What the validity checks of docs/model.md ("Where the model stops holding")
// need at one state, taken from an evaluation of the right-hand side: no
// extra landscape evaluation.
struct ModelMargins {
  // NaN until filled: margins a step failed to fill read as not finite
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  // E = C'^T C' counts as singular at or below this determinant
  static constexpr double kSingularE = 1e-12;
  double normal_force = kUnset;  // F . N = m g0 N_z - m r (N' alpha') . (omega x N)
  double det_E = kUnset;         // det(C'^T C')
  // The ball's fit at the contact, M = phi'^T C' = I - r II (the first
  // fundamental form minus r times the second): positive definite exactly
  // when r max(k1, k2) < 1, so no curvature is needed to test it.
  double fit_xx = kUnset, fit_xy = kUnset, fit_yy = kUnset;
  double slope_x = kUnset, slope_y = kUnset;  // fx, fy: I, for r_kappa_max

  // r max(k1, k2) < 1, as one branch-free test (NaN fails it)
  bool ball_fits() const { return (fit_xx > 0.0) & (fit_xx * fit_yy - fit_xy * fit_xy > 0.0); }
  // the contact is regular: the ball fits and E is not singular
  bool regular() const { return ball_fits() & (det_E > kSingularE); }
  // r max(k1, k2) >= 1/2, where the radius of curvature is at most twice the
  // ball's: I - 2 r II = 2 M - I is not positive definite (false for NaN).
  // The adaptive driver checks the paths of its steps from there on.
  bool near_curvature_limit() const {
    const double a = 2.0 * fit_xx - (1.0 + slope_x * slope_x), b = 2.0 * fit_xy - slope_x * slope_y;
    const double c = 2.0 * fit_yy - (1.0 + slope_y * slope_y);
    return (a <= 0.0) | (a * c - b * b <= 0.0);
  }
  // r max(k1, k2) = 1 - (the smaller eigenvalue of I^-1 M), for messages
  double r_kappa_max() const;
};

// Read access to R stored row by row in a flat state.
template <class T>
struct RowMajorRotation {
  const T* p;
  const T& operator()(int i, int j) const { return p[3 * i + j]; }
};

// Everything the equations of motion need at one state (v, alpha), in the
// world frame. Shapes: N 3, N' 3x2, C' 3x2, E 2x2.
template <class T>
struct Kinematics {
  using V2 = Eigen::Matrix<T, 2, 1>;
  using V3 = Eigen::Matrix<T, 3, 1>;
  V3 N;                        // upward unit normal
  Eigen::Matrix<T, 3, 2> N_d;  // N' = dN / d(x, y)
  Eigen::Matrix<T, 3, 2> C_d;  // C' = phi' + r N'
  Eigen::Matrix<T, 2, 2> E;    // C'^T C'
  T det_E;
  V3 omega;      // angular velocity, world frame
  V2 alpha_dot;  // contact point velocity
  V3 v_dot;      // rate of the angular momentum about the contact
  Jet2<T> f;     // landscape gradient and Hessian; f.f is NaN (not needed)
};

// Derived quantities at one flat state (docs/model.md, "Derived quantities").
struct Derived {
  Vec3 N;                  // upward unit normal at the contact
  Vec3 centre;             // c = phi + r N
  Vec3 centre_velocity;    // c' = r omega x N
  Vec3 omega;              // world frame
  double energy;           // H = 1/2 omega^T T omega + m g0 c_z
  double spin;             // s = omega . N
  double normal_force;     // F . N, F = m c'' - m g
  double kappa1, kappa2;   // principal curvatures, kappa1 >= kappa2, > 0 concave
  double det_E;            // det(C'^T C'): 0 where the contact is singular
  double rotation_defect;  // ||R^T R - I||_F
  double det_defect;       // det R - 1
};

class RollingBall {
 public:
  RollingBall(Landscape landscape, BallParams params);

  const Landscape& landscape() const { return landscape_; }
  const BallParams& params() const { return p_; }
  // Whether R enters the motion: principal moments given and not all equal
  // (equal ones, I = theta, make a ball as symmetric as the homogeneous one).
  bool anisotropic() const { return anisotropic_; }

  // The equations of motion at orientation R and z = (v, alpha); R is read
  // as R(i, j) and only for an anisotropic ball. General = false is the
  // homogeneous ball's code with its constants; true serves a scene with
  // inertia (equal moments or not). Always inlined, so that in lie_rhs and
  // flat_rhs the parts they do not return are never stored.
  template <bool General, class T, class Rot>
  [[gnu::always_inline]] inline Kinematics<T> kinematics(const Rot& R, const T* z) const;
  // The same, choosing General from the ball (for code off the hot path).
  template <class T, class Rot>
  Kinematics<T> kinematics(const Rot& R, const T* z) const {
    return general_ ? kinematics<true>(R, z) : kinematics<false>(R, z);
  }

  // Lie-group view: omega(R, z) and G(R, z) = (v', alpha') in one pass.
  // z and dz hold kZSize numbers; omega 3. A ball with inertia takes an
  // out-of-line copy, so that the homogeneous ball's inlined code is what
  // it was before there were others.
  template <class T>
  [[gnu::always_inline]] void lie_rhs(const Mat3& R, const T* z, T* omega, T* dz) const {
    if (general_) [[unlikely]]
      return lie_rhs_general(R, z, omega, dz);
    store_lie(kinematics<false>(R, z), omega, dz);
  }
  // The same, also filling the validity margins at (R, z).
  [[gnu::always_inline]] void lie_rhs(const Mat3& R, const double* z, double* omega, double* dz,
                                      ModelMargins& margins) const {
    margins = lie_rhs_margins(R, z, omega, dz);
  }
  // The same, returning the margins: a stage that takes them by value keeps
  // them in registers (filled through a reference they stayed in memory,
  // their NaN initialisation stored before the landscape's call).
  [[gnu::always_inline]] ModelMargins lie_rhs_margins(const Mat3& R, const double* z, double* omega, double* dz) const {
    if (general_) [[unlikely]]
      return lie_rhs_general_margins(R, z, omega, dz);
    const Kinematics<double> k = kinematics<false>(R, z);
    store_lie(k, omega, dz);
    return margins_of(k);
  }

  // Whether the ball has principal moments (the general code path of
  // kinematics), equal or not.
  bool has_inertia() const { return general_; }
  // The Lie view with margins on the code path chosen at compile time
  // (General = has_inertia()): a stepper that picks it once per run has a
  // ball with inertia's evaluation inlined into its stages as well, the
  // kinematics in registers instead of an out-of-line call (callgrind, a
  // stage of rkmk-verner7-adaptive on chaplygin-bumpy-long: see
  // docs/performance-history.md).
  template <bool General>
  [[gnu::always_inline]] void lie_rhs_on_path(const Mat3& R, const double* z, double* omega, double* dz,
                                              ModelMargins& margins) const {
    const Kinematics<double> k = kinematics<General>(R, z);
    store_lie(k, omega, dz);
    margins = margins_of(k);
  }

  // Flat view: y' = F(y) for y in R^14 (R row-major, v, alpha); R' = hat(omega) R.
  template <class T>
  [[gnu::always_inline]] void flat_rhs(const T* y, T* dy) const {
    if (general_) [[unlikely]]
      return flat_rhs_general(y, dy);
    store_flat(kinematics<false>(RowMajorRotation<T>{y + kOffsetR}, y + kOffsetV), y, dy);
  }
  // The same, also filling the validity margins at y.
  [[gnu::always_inline]] void flat_rhs(const double* y, double* dy, ModelMargins& margins) const {
    if (general_) [[unlikely]]
      return flat_rhs_general(y, dy, margins);
    const Kinematics<double> k = kinematics<false>(RowMajorRotation<double>{y + kOffsetR}, y + kOffsetV);
    store_flat(k, y, dy);
    margins = margins_of(k);
  }

  // The margins at a flat state, by one evaluation (for a state no stage
  // of the method evaluates: the end of a run, a start).
  ModelMargins margins_at(const FlatState& y) const;

  // T^-1 v: the angular velocity from the angular momentum about the
  // contact point, at orientation R (used only for an anisotropic ball).
  Vec3 omega_from_momentum(const Mat3& R, const Vec3& N, const Vec3& v) const;
  // T omega = R Theta R^T omega + m r^2 (omega - N (N . omega)).
  Vec3 momentum_from_omega(const Mat3& R, const Vec3& N, const Vec3& omega) const;
  // T(R, alpha) itself, for tests and derived quantities.
  Mat3 contact_inertia(const Mat3& R, const Vec3& N) const;

  // The upward unit normal at the contact point (x, y).
  Vec3 normal_at(double x, double y) const;

  // Every derived quantity of docs/model.md at a flat state.
  Derived derived(const FlatState& y) const;

 private:
  // the out-of-line copies for a ball with inertia
  template <class T>
  [[gnu::noinline]] void lie_rhs_general(const Mat3& R, const T* z, T* omega, T* dz) const {
    store_lie(kinematics<true>(R, z), omega, dz);
  }
  [[gnu::noinline]] ModelMargins lie_rhs_general_margins(const Mat3& R, const double* z, double* omega,
                                                         double* dz) const {
    const Kinematics<double> k = kinematics<true>(R, z);
    store_lie(k, omega, dz);
    return margins_of(k);
  }
  template <class T>
  [[gnu::noinline]] void flat_rhs_general(const T* y, T* dy) const {
    store_flat(kinematics<true>(RowMajorRotation<T>{y + kOffsetR}, y + kOffsetV), y, dy);
  }
  [[gnu::noinline]] void flat_rhs_general(const double* y, double* dy, ModelMargins& margins) const {
    const Kinematics<double> k = kinematics<true>(RowMajorRotation<double>{y + kOffsetR}, y + kOffsetV);
    store_flat(k, y, dy);
    margins = margins_of(k);
  }

  template <class T>
  [[gnu::always_inline]] static void store_lie(const Kinematics<T>& k, T* omega, T* dz) {
    for (int i = 0; i < 3; ++i) omega[i] = k.omega[i];
    for (int i = 0; i < 3; ++i) dz[i] = k.v_dot[i];
    dz[3] = k.alpha_dot[0];
    dz[4] = k.alpha_dot[1];
  }
  template <class T>
  [[gnu::always_inline]] static void store_flat(const Kinematics<T>& k, const T* y, T* dy) {
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
  // Inlined into the step's first stage, so that it reads the kinematics
  // from registers.
  [[gnu::always_inline]] ModelMargins margins_of(const Kinematics<double>& k) const;

  // omega = T^-1 v for the anisotropic ball by Sherman-Morrison (docs/model.md):
  // in the body frame, with d = 1 / (Theta + m r^2), n = R^T N, b = R^T v,
  // omega = R (d b + m r^2 (d n . b) / (1 - m r^2 n . d n) d n).
  // Inlined into kinematics (out of line it took 114 instructions a call,
  // N, v and w passed through memory).
  template <class T, class Rot>
  [[gnu::always_inline]] void anisotropic_omega(const Rot& R, const T (&N)[3], const T* v, T (&w)[3]) const;

  Landscape landscape_;
  BallParams p_;
  bool general_ = false;       // inertia given: the general code path
  bool anisotropic_ = false;   // and the moments are not all equal
  Vec3 inv_d_ = Vec3::Zero();  // 1 / (I_k + m r^2), anisotropic ball only
  double theta_ = 0.0;         // the moment of a ball with equal ones
  double iso_scale_ = 0.0;     // s and c of T^-1 for equal moments (see kinematics)
  double iso_normal_ = 0.0;
  // m r^2 and m r g0, computed once: every evaluation formed them (and the
  // homogeneous ball's (5 / 7) / (m r^2), now iso_scale_, by a division),
  // the ball's parameters read again after each call of the landscape
  double mr2_ = 0.0;
  double mrg_ = 0.0;
};

inline ModelMargins RollingBall::margins_of(const Kinematics<double>& k) const {
  ModelMargins m;
  // F = m c'' - m g with c'' = r (omega' x N + omega x N_dot): the omega'
  // term is normal to N, so F . N needs no omega'. N_dot = N' alpha' and
  // omega x N are kinematics' d and q: written as the same operations on
  // the same scalars, GCC reuses them (with Eigen's products it formed
  // them again); the dot's order is Eigen's, (d0 q0 + d1 q1) + d2 q2.
  const double ax = k.alpha_dot[0], ay = k.alpha_dot[1];
  const double d0 = k.N_d(0, 0) * ax + k.N_d(0, 1) * ay, d1 = k.N_d(1, 0) * ax + k.N_d(1, 1) * ay,
               d2 = k.N_d(2, 0) * ax + k.N_d(2, 1) * ay;
  const double w0 = k.omega[0], w1 = k.omega[1], w2 = k.omega[2], N0 = k.N[0], N1 = k.N[1], N2 = k.N[2];
  const double q0 = w1 * N2 - w2 * N1, q1 = w2 * N0 - w0 * N2, q2 = w0 * N1 - w1 * N0;
  m.normal_force = p_.mass * (p_.gravity * N2 - p_.radius * ((d0 * q0 + d1 * q1) + d2 * q2));
  m.det_E = k.det_E;
  // M = phi'^T C' with phi' = [[1, 0], [0, 1], [fx, fy]]
  m.fit_xx = k.C_d(0, 0) + k.f.fx * k.C_d(2, 0);
  m.fit_xy = k.C_d(0, 1) + k.f.fx * k.C_d(2, 1);
  m.fit_yy = k.C_d(1, 1) + k.f.fy * k.C_d(2, 1);
  m.slope_x = k.f.fx;
  m.slope_y = k.f.fy;
  return m;
}

template <class T, class Rot>
[[gnu::always_inline]] inline void RollingBall::anisotropic_omega(const Rot& R, const T (&N)[3], const T* v,
                                                                  T (&w)[3]) const {
  const double mr2 = p_.mass * p_.radius * p_.radius;
  T dn[3], db[3];
  T ndn = T(0.0), dnb = T(0.0);
  for (int j = 0; j < 3; ++j) {
    const T n = R(0, j) * N[0] + R(1, j) * N[1] + R(2, j) * N[2];
    const T b = R(0, j) * v[0] + R(1, j) * v[1] + R(2, j) * v[2];
    dn[j] = inv_d_[j] * n;
    db[j] = inv_d_[j] * b;
    ndn += n * dn[j];
    dnb += dn[j] * b;
  }
  const T coef = mr2 * dnb / (1.0 - mr2 * ndn);
  T wb[3];
  for (int j = 0; j < 3; ++j) wb[j] = db[j] + coef * dn[j];
  for (int i = 0; i < 3; ++i) w[i] = R(i, 0) * wb[0] + R(i, 1) * wb[1] + R(i, 2) * wb[2];
}

// Written out in scalars rather than with Eigen's 3-vectors: this is the hot
// path of every integrator, and scalar code lets the compiler keep the whole
// state in registers (Eigen's fixed-size temporaries cost about a third more
// per evaluation here).
template <bool General, class T, class Rot>
Kinematics<T> RollingBall::kinematics(const Rot& R, const T* z) const {
  using std::sqrt;
  Kinematics<T> k;
  const double r = p_.radius;
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

  // omega = T^-1 v; for equal moments theta: (v + c N (N . v)) s with
  // s = 1 / (theta + m r^2), c = m r^2 / theta (homogeneous: s = (5/7) / (m r^2), c = 5/2)
  T w0, w1, w2;
  if constexpr (!General) {
    const double s = iso_scale_;  // (5 / 7) / (m r^2), computed once (the constructor)
    const T Nv = 2.5 * (N0 * z[0] + N1 * z[1] + N2 * z[2]);
    w0 = (z[0] + N0 * Nv) * s, w1 = (z[1] + N1 * Nv) * s, w2 = (z[2] + N2 * Nv) * s;
  } else if (anisotropic_) {
    T w[3];
    anisotropic_omega(R, {N0, N1, N2}, z, w);
    w0 = w[0], w1 = w[1], w2 = w[2];
  } else {
    const double s = iso_scale_;
    const T Nv = iso_normal_ * (N0 * z[0] + N1 * z[1] + N2 * z[2]);
    w0 = (z[0] + N0 * Nv) * s, w1 = (z[1] + N1 * Nv) * s, w2 = (z[2] + N2 * Nv) * s;
  }

  // alpha' = r E^-1 C'^T (omega x N), with the 2x2 inverse written out
  const T q0 = w1 * N2 - w2 * N1, q1 = w2 * N0 - w0 * N2, q2 = w0 * N1 - w1 * N0;
  const T b0 = Cx0 * q0 + Cx1 * q1 + Cx2 * q2, b1 = Cy0 * q0 + Cy1 * q1 + Cy2 * q2;
  const T inv_det = r / det_E;
  const T ax = (E11 * b0 - E01 * b1) * inv_det, ay = (E00 * b1 - E01 * b0) * inv_det;

  // v' = m r (N x g) - m r^2 (N' alpha') x (N x omega), g = (0, 0, -g0);
  // N x omega = -(omega x N) = -q
  const T d0 = Nx0 * ax + Ny0 * ay, d1 = Nx1 * ax + Ny1 * ay, d2 = Nx2 * ax + Ny2 * ay;  // N' alpha'
  const double mrg = mrg_, mr2 = mr2_;

  // element by element, not with Eigen's comma initializer: GCC calls that
  // out of line (36 instructions a step of rk4, callgrind), and a call
  // keeps the stores alive that the callers never read
  k.N = {N0, N1, N2};
  k.N_d(0, 0) = Nx0, k.N_d(0, 1) = Ny0, k.N_d(1, 0) = Nx1, k.N_d(1, 1) = Ny1, k.N_d(2, 0) = Nx2, k.N_d(2, 1) = Ny2;
  k.C_d(0, 0) = Cx0, k.C_d(0, 1) = Cy0, k.C_d(1, 0) = Cx1, k.C_d(1, 1) = Cy1, k.C_d(2, 0) = Cx2, k.C_d(2, 1) = Cy2;
  k.E(0, 0) = E00, k.E(0, 1) = E01, k.E(1, 0) = E01, k.E(1, 1) = E11;
  k.det_E = det_E;
  k.omega = {w0, w1, w2};
  k.alpha_dot = {ax, ay};
  k.v_dot = {-mrg * N1 + mr2 * (d1 * q2 - d2 * q1), mrg * N0 + mr2 * (d2 * q0 - d0 * q2), mr2 * (d0 * q1 - d1 * q0)};
  return k;
}

}  // namespace rb

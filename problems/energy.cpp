#include "problems/energy.hpp"

#include <limits>

#include "problems/so3.hpp"

namespace rb {

double flat_energy(const RollingBall& ball, const FlatState& y, FlatState* grad) {
  const BallParams& p = ball.params();
  const double r = p.radius, m = p.mass, g0 = p.gravity, mr2 = m * r * r;
  const double* z = y.data() + kOffsetV;
  const Kinematics<double> k = ball.kinematics(RowMajorRotation<double>{y.data() + kOffsetR}, z);
  const Vec3 v = momentum_of(y);
  // as derived(): H = 1/2 omega . v + m g0 (f + r N_z)
  const double energy = 0.5 * k.omega.dot(v) + m * g0 * (ball.landscape().height(z[3], z[4]) + r * k.N.z());
  if (!grad) return energy;
  FlatState& g = *grad;

  // omega = A v with A = T^-1 symmetric, so dH/dv = omega. T = (R Theta R^T,
  // or theta I) + m r^2 (I - N N^T): a change dN changes A by A m r^2 (dN
  // N^T + N dN^T) A, so dH = m r^2 (omega . N)(omega . dN) with dN = N'
  // d alpha; the height adds m g0 (f_k + r N'_z,k).
  g.segment<3>(kOffsetV) = k.omega;
  const double wN = k.omega.dot(k.N);
  const double slope[2] = {k.f.fx, k.f.fy};
  for (int c = 0; c < 2; ++c)
    g[kOffsetAlpha + c] = mr2 * wN * k.omega.dot(k.N_d.col(c)) + m * g0 * (slope[c] + r * k.N_d(2, c));

  // R enters only the anisotropic ball's A = (B^-1 - m r^2 N N^T)^-1, B =
  // R D R^T, D = (Theta + m r^2)^-1, as kinematics computes it for any
  // matrix R (Sherman-Morrison): dA = A B^-1 dB B^-1 A gives dH/dR = u w^T
  // with w = R^-1 omega, u = R^-T D^-1 w (on SO(3), R^-1 = R^T).
  g.segment<9>(kOffsetR).setZero();
  if (ball.anisotropic()) {
    const Mat3 R = rotation_of(y), R_inv = R.inverse();
    const Vec3 w = R_inv * k.omega;
    const Vec3 u = R_inv.transpose() * (w.array() * (p.inertia->array() + mr2)).matrix();
    Eigen::Map<RowMajorMat3>(g.data() + kOffsetR) = u * w.transpose();
  }
  return energy;
}

double energy_on_group(const RollingBall& ball, const FlatState& y) {
  if (!ball.anisotropic()) return flat_energy(ball, y);
  const Mat3 R = rotation_of(y);
  if (!R.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  FlatState on_group = y;
  set_rotation(on_group, project_to_so3(R));
  return flat_energy(ball, on_group);
}

}  // namespace rb

#pragma once
// The Lie midpoint rule on SO(3) x R^5 (docs/model.md, "Symmetric implicit
// methods"): with xi(R, z) = (omega(R, z), G(R, z)) acting on (R, z) by
// (theta, w) . (R, z) = (exp(hat(theta)) R, z + w), one step solves
//   theta = h omega(R_m, z_m),  w = h G(R_m, z_m),
//   (R_m, z_m) = (exp(theta / 2) R_n, z_n + w / 2),
// and sets (R_{n+1}, z_{n+1}) = (exp(theta) R_n, z_n + w). It is symmetric:
// the midpoint is exp(-theta/2) applied to the step's end as well, so the
// step back from y_{n+1} with -h solves the same equations with -(theta, w).
// No dexpinv enters (with one, as RKMK on the midpoint tableau, it would not
// be symmetric: dexpinv_{-u} != dexpinv_u). The unknowns are the half step
// U = theta / 2, W = w / 2, solved by newton.hpp with the Jacobian of
// (U, W) -> xi(exp(U) R_n, z_n + W) at 0, taken from the flat view's AD
// Jacobian (lie_jacobian).
#include <Eigen/Dense>

#include "integrators/integrator.hpp"
#include "problems/jacobian.hpp"

namespace rb {

using LieJacobian = Eigen::Matrix<double, 3 + kZSize, 3 + kZSize>;

// d xi(exp(U) R, z + W) / d(U, W) at (0, 0), from the flat Jacobian J and
// F(y) = f at y = (R, z): F's R rows are hat(omega) R, so omega = vee(R'
// R^T), and a change dR = hat(e_k) R of R moves omega by vee((dR' -
// hat(omega) dR) R^T).
LieJacobian lie_jacobian(const FlatJacobian& J, const FlatState& f, const Mat3& R);

struct LieMidpointStep {
  const Problem& problem;
  bool anisotropic;  // R enters xi: the midpoint's orientation is computed
  FlatJacobian J;
  FlatState f;
  Eigen::MatrixXd M;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::VectorXd X, r, dX, scale;

  explicit LieMidpointStep(const Problem& p);
  void operator()(const FlatState& y, FlatState& next, double t, double h, Cost& cost);
};

}  // namespace rb

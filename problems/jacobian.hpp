#pragma once
// The exact Jacobian of the flat view F(y) (docs/model.md, "Integrators
// compared"), for the implicit integrators: forward-mode automatic
// differentiation through Problem::flat_rhs, so there is no finite-difference
// step to choose and the result is exact up to rounding.
#include <Eigen/Dense>

#include "problems/problem.hpp"

namespace rb {

// 14 x 14, row-major: J(i, j) = dF_i / dy_j, the layout GSL's dfdy expects.
using FlatJacobian = Eigen::Matrix<double, kFlatSize, kFlatSize, Eigen::RowMajor>;

// J = dF/dy at the flat state y, and F(y) itself into *f when f is not null
// (the values come for free with the derivatives). One call costs about as
// much as 14 evaluations of F. Never allocates; never throws. Where F is not
// finite, neither is J.
void flat_jacobian(const Problem& problem, const FlatState& y, FlatJacobian& J, FlatState* f = nullptr);

}  // namespace rb

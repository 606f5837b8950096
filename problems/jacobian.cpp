#include "problems/jacobian.hpp"

#include <unsupported/Eigen/AutoDiff>

namespace rb {

namespace {

// A number with 14 fixed-size partial derivatives: no heap allocation.
using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, kFlatSize, 1>>;

}  // namespace

void flat_jacobian(const Problem& problem, const FlatState& y, FlatJacobian& J, FlatState* f) {
  // seed y_j with the j-th unit derivative; one pass then carries dF/dy_j
  // along in every intermediate value
  Ad y_ad[kFlatSize];
  Ad dy_ad[kFlatSize];
  for (int j = 0; j < kFlatSize; ++j) y_ad[j] = Ad(y[j], kFlatSize, j);
  problem.flat_rhs(y_ad, dy_ad);
  for (int i = 0; i < kFlatSize; ++i) {
    J.row(i) = dy_ad[i].derivatives().transpose();
    if (f) (*f)[i] = dy_ad[i].value();
  }
}

}  // namespace rb

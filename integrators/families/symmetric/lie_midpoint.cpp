#include "integrators/families/symmetric/lie_midpoint.hpp"

#include "integrators/families/rkmk/rkmk_stepper.hpp"
#include "integrators/steppers/newton.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

constexpr int kLieSize = 3 + kZSize;

// The axial vector of the skew part of S.
Vec3 vee_skew(const Mat3& S) { return 0.5 * Vec3(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1)); }

}  // namespace

LieJacobian lie_jacobian(const FlatJacobian& J, const FlatState& f, const Mat3& R) {
  const Mat3 Rdot = Eigen::Map<const RowMajorMat3>(f.data() + kOffsetR);
  const Mat3 omega_hat = hat(vee_skew(Rdot * R.transpose()));
  LieJacobian L;
  for (int k = 0; k < kLieSize; ++k) {
    // the change of the flat state for a unit change of U_k or W_k
    FlatState dy = FlatState::Zero();
    Mat3 dR = Mat3::Zero();
    if (k < 3) {
      dR = hat(Vec3::Unit(k)) * R;
      Eigen::Map<RowMajorMat3>(dy.data() + kOffsetR) = dR;
    } else {
      dy[kOffsetV + k - 3] = 1.0;
    }
    const FlatState dF = J * dy;
    const Mat3 dRdot = Eigen::Map<const RowMajorMat3>(dF.data() + kOffsetR);
    L.block<3, 1>(0, k) = vee_skew((dRdot - omega_hat * dR) * R.transpose());
    L.block<kZSize, 1>(3, k) = dF.tail<kZSize>();
  }
  return L;
}

LieMidpointStep::LieMidpointStep(const Problem& p) : problem(p), anisotropic(p.model().anisotropic()) {
  M.resize(kLieSize, kLieSize);
  lu = Eigen::PartialPivLU<Eigen::MatrixXd>(kLieSize);
  X.resize(kLieSize);
  r.resize(kLieSize);
  dX.resize(kLieSize);
  scale.resize(kLieSize);
}

void LieMidpointStep::operator()(const FlatState& y, FlatState& next, double t, double h, Cost& cost) {
  const Mat3 Rn = rotation_of(y);
  const ZState z = z_of(y);
  flat_jacobian(problem, y, J, &f);
  ++cost.jacobian_evals;
  cost.jacobian_columns += kFlatSize;
  M = Eigen::MatrixXd::Identity(kLieSize, kLieSize) - (0.5 * h) * lie_jacobian(J, f, Rn);
  // lie_jacobian: one product of the 14x14 J with a vector per unknown
  cost.linear_algebra_flops += 2.0 * kLieSize * kFlatSize * kFlatSize;
  lu.compute(M);
  cost.note_decomposition(kLieSize);
  X.setZero();
  scale.head<3>().setOnes();  // U in radians
  scale.tail<kZSize>() = (1.0 + z.array().abs()).inverse().matrix();
  Vec3 omega;
  ZState G;
  auto residual = [&](const Eigen::VectorXd& UW, Eigen::VectorXd& res, bool first) {
    if (first) {
      // at U = W = 0 the midpoint is y_n: the Jacobian's own F(y_n)
      const Mat3 Rdot = Eigen::Map<const RowMajorMat3>(f.data() + kOffsetR);
      omega = vee_skew(Rdot * Rn.transpose());
      G = f.tail<kZSize>();
    } else {
      const ZState Z = z + UW.tail<kZSize>();
      if (anisotropic) {
        stage_lie_rhs(problem, Mat3(so3_exp(UW.head<3>()) * Rn), Z.data(), omega.data(), G.data(), cost);
        ++cost.exp_evals;
      } else {
        // the homogeneous ball's xi does not read R
        stage_lie_rhs(problem, kAnyRotation, Z.data(), omega.data(), G.data(), cost);
      }
      ++cost.rhs_evals;
    }
    res.head<3>() = UW.head<3>() - (0.5 * h) * omega;
    res.tail<kZSize>() = UW.tail<kZSize>() - (0.5 * h) * G;
  };
  newton_solve(lu, scale, X, r, dX, residual, t, h, cost);
  set_rotation(next, so3_exp(2.0 * Vec3(X.head<3>())) * Rn);
  next.tail<kZSize>() = z + 2.0 * X.tail<kZSize>();
  ++cost.exp_evals;
}

}  // namespace rb

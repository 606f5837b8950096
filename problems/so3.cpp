#include "problems/so3.hpp"

#include <Eigen/SVD>

namespace rb {

Mat3 project_to_so3(const Mat3& M) {
  Eigen::JacobiSVD<Mat3> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 D = Mat3::Identity();
  // keep det = +1 (a reflection is not a rotation)
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) D(2, 2) = -1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

double rotation_angle_between(const Mat3& R_a, const Mat3& R_b) {
  const Mat3 Q = project_to_so3(R_a).transpose() * project_to_so3(R_b);
  // the angle from the antisymmetric part is accurate for small angles,
  // where acos((tr - 1) / 2) loses half the digits
  const Vec3 s(Q(2, 1) - Q(1, 2), Q(0, 2) - Q(2, 0), Q(1, 0) - Q(0, 1));
  return std::atan2(0.5 * s.norm(), 0.5 * (Q.trace() - 1.0));
}

// dexpinv_coefficient from t^2 = 1e-2 on.
double dexpinv_coefficient_wide(double t2) {
  if (t2 < 1.0)
    return 1.0 / 12.0 +
           t2 * (1.0 / 720.0 +
                 t2 * (1.0 / 30240.0 +
                       t2 * (1.0 / 1209600.0 +
                             t2 * (1.0 / 47900160.0 +
                                   t2 * (691.0 / 1307674368000.0 +
                                         t2 * (1.0 / 74724249600.0 +
                                               t2 * (3617.0 / 10670622842880000.0 +
                                                     t2 * (43867.0 / 5109094217170944000.0 +
                                                           t2 * (174611.0 / 802857662698291200000.0)))))))));
  if (!(t2 < kDexpinvMaxAngle * kDexpinvMaxAngle)) return std::numeric_limits<double>::quiet_NaN();
  const double t = std::sqrt(t2);
  return (1.0 - 0.5 * t / std::tan(0.5 * t)) / t2;
}

}  // namespace rb

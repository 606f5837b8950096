#pragma once
// The state of the rolling ball in its two views (docs/model.md, "Integrators
// compared"), as fixed-size Eigen types: nothing here allocates.
#include <Eigen/Dense>

namespace rb {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

// Flat view: y = (R's 9 entries row by row, v, alpha), 14 numbers.
inline constexpr int kFlatSize = 14;
// Lie-group view: z = (v, alpha), 5 numbers; R is kept apart.
inline constexpr int kZSize = 5;
// Offsets into the flat state.
inline constexpr int kOffsetR = 0;
inline constexpr int kOffsetV = 9;
inline constexpr int kOffsetAlpha = 12;

using FlatState = Eigen::Matrix<double, kFlatSize, 1>;
using ZState = Eigen::Matrix<double, kZSize, 1>;
using RowMajorMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// R from the flat state (row-major storage).
inline Mat3 rotation_of(const FlatState& y) { return Eigen::Map<const RowMajorMat3>(y.data() + kOffsetR); }
inline void set_rotation(FlatState& y, const Mat3& R) { Eigen::Map<RowMajorMat3>(y.data() + kOffsetR) = R; }
// v (angular momentum about the contact point, world frame).
inline Vec3 momentum_of(const FlatState& y) { return y.segment<3>(kOffsetV); }
// alpha = (x, y), the contact point's coordinates.
inline Vec2 contact_of(const FlatState& y) { return y.segment<2>(kOffsetAlpha); }
// z = (v, alpha), the tail of the flat state.
inline ZState z_of(const FlatState& y) { return y.tail<kZSize>(); }

inline FlatState make_flat(const Mat3& R, const Vec3& v, const Vec2& alpha) {
  FlatState y;
  set_rotation(y, R);
  y.segment<3>(kOffsetV) = v;
  y.segment<2>(kOffsetAlpha) = alpha;
  return y;
}

}  // namespace rb

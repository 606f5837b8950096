#pragma once
// The Cayley map of so(3) and the inverse of its derivative, in closed form:
// the coordinate map of rkmk4-cayley (docs/model.md, "The methods compared", with cay in place
// of exp). cay is rational (no sin, cos or square root) and has no pole on
// R^3, where exp's dexpinv has one at |u| = 2 pi.
#include "problems/so3.hpp"

namespace rb {

// cay(u) = (I - hat(u)/2)^-1 (I + hat(u)/2)
//        = I + (4 / (4 + |u|^2)) (hat(u) + hat(u)^2 / 2),
// from (I - A)^-1 (I + A) = I + 2 (A + A^2) / (1 + |a|^2) for A = hat(a),
// a = u / 2. It agrees with exp(hat(u)) to O(|u|^3).
inline Mat3 so3_cay(const Vec3& u) {
  const double s = 4.0 / (4.0 + u.squaredNorm());
  const Mat3 U = hat(u);
  return Mat3::Identity() + s * (U + 0.5 * U * U);
}

// dcayinv_u(w): the u' for which d/dt cay(u(t)) = hat(w) cay(u). From
// (I - U/2) C = I + U/2, U = hat(u), C = cay(u): C' C^-1 = (I - U/2)^-1 U'
// (I + U/2)^-1, so U' = (I - U/2) hat(w) (I + U/2) = hat(w) - [U, hat(w)] / 2
// - U hat(w) U / 4, and U hat(w) U = -(u . w) U:
// dcayinv_u(w) = w - u x w / 2 + (u . w) u / 4.
inline Vec3 dcayinv(const Vec3& u, const Vec3& w) { return w - 0.5 * u.cross(w) + 0.25 * u.dot(w) * u; }

}  // namespace rb

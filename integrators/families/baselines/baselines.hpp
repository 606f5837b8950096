#pragma once
// What practitioners do instead of a Lie-group method, as baselines for it:
// a classical method whose rotation is pulled back onto SO(3) after every
// step. Both are RK4 (4 rhs evaluations a step), fixed-step, order 4, each a
// stepper functor made an integrator by stepped_method. Their RK4 is written
// out (rk4_step), not summed from methods/rk4.hpp: the same method, whose
// sums are in another order.
//
// - rk4-projected (family "projection", RotationFix::project_newton_schulz):
//   RK4 on the flat view y in R^14, then R <- the closest rotation to R (its
//   polar factor, by Newton-Schulz steps, rb::project_to_so3_newton_schulz:
//   one step of two 3x3 products after a step of RK4). A step: 4 flat rhs
//   evaluations and one projection.
//   rk4-projected-svd (RotationFix::project_svd): the same with the polar
//   factor from a 3x3 SVD (rb::project_to_so3), the same rotation at many
//   times the cost.
// - rk4-quaternion (family "quaternion", RotationFix::unit_quaternion): RK4
//   on (q, z) in R^4 x R^5 with q' = 1/2 (0, omega) (x) q (omega from
//   Problem::lie_rhs, world frame, so R(q) is body to world), then
//   q <- q / |q|. A step: 4 Lie-view rhs evaluations, one normalisation, and
//   R(q) for the flat state the run reports (a few dozen flops).
#include <memory>
#include <string>

#include "integrators/integrator.hpp"

namespace rb {

// How a baseline keeps R a rotation after each RK4 step: the method data of
// its registry line.
enum class RotationFix {
  project_newton_schulz,  // the polar factor by Newton-Schulz (family "projection")
  project_svd,            // the polar factor by a 3x3 SVD (family "projection")
  unit_quaternion,        // RK4 on a unit quaternion, normalised (family "quaternion")
};

// RK4 with the rotation fix, called name; fixed steps only: InputError
// (key "controller") for any controller but "constant".
std::unique_ptr<Integrator> rk4_baseline(RotationFix fix, std::string name, const std::string& controller);

}  // namespace rb

#pragma once
// The energy on the flat view and its exact gradient, for the
// discrete-gradient method (docs/model.md, "A discrete-gradient method"),
// and the energy at the nearest rotation, which the report measures beside
// the flat one (docs/model.md, "How the energy error is measured").
#include "problems/rolling_ball.hpp"

namespace rb {

// H(y) = 1/2 omega . v + m g0 c_z at the flat state y, as derived() computes
// it, and, where grad is not null, dH/dy over the 14 flat components in
// closed form. R is read as the 3x3 matrix it is, rotation or not (as the
// flat view's F reads it), and grad H . F = 0 holds there too. One pass of
// the kinematics and one of the height; never throws.
double flat_energy(const RollingBall& ball, const FlatState& y, FlatState* grad = nullptr);

// H(polar(R), v, alpha): the energy of the real ball at the state's v and
// alpha, turned by the rotation nearest R (its orthogonal polar factor with
// det +1, project_to_so3). The flat H is conserved by the flat flow for any
// matrix R, as the energy of a ball whose inertia R's drift off SO(3) has
// deformed, so a method whose R drifts may keep the flat H and still move
// this one. It equals flat_energy where R is a rotation and, for the
// homogeneous ball (whose H does not read R), everywhere. NaN where R is
// not finite; never throws.
double energy_on_group(const RollingBall& ball, const FlatState& y);

}  // namespace rb

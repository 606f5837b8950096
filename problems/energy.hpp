#pragma once
// The energy on the flat view and its exact gradient, for the
// discrete-gradient method (docs/model.md, "A discrete-gradient method").
#include "problems/rolling_ball.hpp"

namespace rb {

// H(y) = 1/2 omega . v + m g0 c_z at the flat state y, as derived() computes
// it, and, where grad is not null, dH/dy over the 14 flat components in
// closed form. R is read as the 3x3 matrix it is, rotation or not (as the
// flat view's F reads it), and grad H . F = 0 holds there too. One pass of
// the kinematics and one of the height; never throws.
double flat_energy(const RollingBall& ball, const FlatState& y, FlatState* grad = nullptr);

}  // namespace rb

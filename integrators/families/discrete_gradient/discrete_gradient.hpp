#pragma once
// The discrete-gradient method dg2 on the flat view (docs/model.md, "A
// discrete-gradient method"): McLachlan, Quispel and Robidoux's skew form
// F = S grad H, S(y) = (F grad H^T - grad H F^T) / |grad H|^2 (Phil. Trans.
// R. Soc. A 357, 1999), with Gonzalez's midpoint discrete gradient:
//   y1 = y0 + h S(ym) dgH(y0, y1),   ym = (y0 + y1) / 2,
//   dgH = grad H(ym) + (H(y1) - H(y0) - grad H(ym) . dy) dy / |dy|^2,
// dy = y1 - y0. dgH . dy = H(y1) - H(y0) and S is skew, so H(y1) = H(y0)
// up to the solve and rounding; it is symmetric and of order 2. Solved by
// newton.hpp with gauss2's matrix I - h/2 J(y0).
#include <memory>
#include <string>

#include "integrators/integrator.hpp"

namespace rb {

// Which discrete gradient the method uses: the method data of its registry
// line. Gonzalez's midpoint discrete gradient (above) is the one there is.
enum class DiscreteGradient { gonzalez_midpoint };

// The discrete-gradient method (family "discrete-gradient"), called name;
// fixed steps only: InputError (key "controller") for any controller but
// "constant".
std::unique_ptr<Integrator> discrete_gradient_method(DiscreteGradient gradient, std::string name,
                                                     const std::string& controller);

}  // namespace rb

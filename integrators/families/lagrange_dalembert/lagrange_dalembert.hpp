#pragma once
// The discrete Lagrange-d'Alembert method dla2 on SO(3) x R^2 (docs/model.md,
// "A discrete Lagrange-d'Alembert method"): configuration q = (R, alpha),
// discrete Lagrangian
//   L_d = phi . Theta phi / (2h) + m |C(alpha1) - C(alpha0)|^2 / (2h)
//         - (h/2) (V(alpha0) + V(alpha1)),  R1 = R0 cay(phi),  V = m g0 C_z,
// variations in the rolling distribution D at the nodes (Cortes-Martinez,
// McLachlan-Perlmutter 2006), and the rolling constraint imposed on the step
// by the trapezoidal rule in the centre's displacement dC:
//   C'(alpha0)^T (dC - r theta x N0) + C'(alpha1)^T (dC - r theta x N1) = 0,
// theta = R0 phi the spatial rotation vector. The momentum restricted to D
// is the state's v (T omega), so a step solves
//   h v0 = R0 dcayinv_{-phi}(Theta phi) + m r N0 x dC - (h^2/2) m r N0 x g
// with the constraint (5 equations for phi, dalpha), then sets
//   v1 = v0 + (m r / h)(N1 - N0) x dC + (h/2) m r (N0 + N1) x g.
// Symmetric (so of order 2) and reversible; R moves by Cayley rotations only.
// Solved by newton.hpp with the Jacobian of the 5 residuals by forward-mode
// AD at an explicit predictor.
#include <memory>
#include <string>

#include "integrators/integrator.hpp"

namespace rb {

// How the rolling constraint is imposed on a step: the method data of its
// registry line. The trapezoidal rule (above) is the one there is.
enum class DiscreteConstraint { trapezoidal };

// The discrete Lagrange-d'Alembert method (family
// "nonholonomic-variational"), called name; fixed steps only: InputError
// (key "controller") for any controller but "constant".
std::unique_ptr<Integrator> lagrange_dalembert_method(DiscreteConstraint constraint, std::string name,
                                                      const std::string& controller);

}  // namespace rb

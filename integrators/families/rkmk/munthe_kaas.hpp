#pragma once
// Runge-Kutta-Munthe-Kaas on the Lie-group view (docs/model.md, "The
// methods compared"), at fixed steps (family "rkmk") and on embedded pairs
// (family "rkmk-adaptive"): both run the one stepper of rkmk_stepper.hpp,
// made by one maker, under the constant controller or under a filter. With
// the Euler tableau this is exp-Euler (Lie-Euler). Registry lines name them
// through rkmk_method and rkmk_cayley_method (tableau_methods.hpp).
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"
#include "problems/so3.hpp"

namespace rb {

// RKMK with exp for coordinates. Controller "constant": fixed steps with the
// tableau's propagating weights and the given dexpinv (family "rkmk"). A
// filter (integrators/controllers/): the tableau's embedded pair with that
// controller as its default (family "rkmk-adaptive"); use_dense = false
// clamps steps onto the outputs even where the tableau has a dense output
// (for tests and comparisons). Throws InputError for a filter with a dexpinv
// other than the closed form, a tableau without embedded weights or an
// unknown controller.
std::unique_ptr<Integrator> rkmk_integrator(Tableau tableau, std::string name, const std::string& controller,
                                            DexpinvKind dexpinv = DexpinvKind::exact, bool use_dense = true);

// The same with the Cayley map for coordinates: u' = dcayinv_u(omega),
// R_{n+1} = cay(u_{n+1}) R_n (problems/cayley.hpp), fixed steps only
// (InputError with a filter). A coordinate map with phi(0) = I and
// dphi_0 = id changes only the coordinates of RKMK, not its order: with RK4
// it stays order 4.
std::unique_ptr<Integrator> rkmk_cayley_integrator(Tableau tableau, std::string name, const std::string& controller);

}  // namespace rb

#pragma once
// Runge-Kutta-Munthe-Kaas at fixed steps on the Lie-group view (docs/model.md,
// "The methods compared"): over a step with R_n fixed, integrate
// u' = dexpinv_u(omega(z)), u(t_n) = 0, together with z' = G(z) by an
// explicit tableau, then R_{n+1} = exp(hat(u_{n+1})) R_n. R stays in SO(3) to
// rounding error. With the Euler tableau this is exp-Euler (Lie-Euler).
// The step itself is rkmk_step.hpp; the adaptive pairs are
// munthe_kaas_adaptive.hpp; registry lines name them through rkmk_method
// (tableau_methods.hpp).
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"
#include "problems/so3.hpp"

namespace rb {

// The fixed-step integrator of the tableau with exp for coordinates and the
// given dexpinv (family "rkmk").
std::unique_ptr<Integrator> rkmk_fixed(Tableau tableau, std::string name, DexpinvKind dexpinv = DexpinvKind::exact);

// The same with the Cayley map for coordinates: u' = dcayinv_u(omega),
// R_{n+1} = cay(u_{n+1}) R_n (problems/cayley.hpp). A coordinate map with
// phi(0) = I and dphi_0 = id changes only the coordinates of RKMK, not its
// order: with RK4 it stays order 4.
std::unique_ptr<Integrator> rkmk_cayley_fixed(Tableau tableau, std::string name);

}  // namespace rb

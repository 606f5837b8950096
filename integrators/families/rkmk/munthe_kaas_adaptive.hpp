#pragma once
// Adaptive Runge-Kutta-Munthe-Kaas on embedded pairs (docs/model.md, "The methods compared",
// with a step-size controller). Over a step with R_n fixed, the pair
// integrates u' = dexpinv_u(omega(z)), u(t_n) = 0, with z' = G(z);
// R_{n+1} = exp(hat(u_{n+1})) R_n, so R stays in SO(3) to rounding error.
//
// - The local error is estimated on (u, z) only, never on R's entries: u's
//   three components are angles, measured against atol + rtol (R's entries
//   are of size 1, as a flat method sees them); z's against
//   atol + rtol max(|z_n,i|, |z_n+1,i|). Norm: root mean square (Hairer's).
// - The step size comes from a controller (integrators/controllers/): by
//   default Gustafsson's PI, RunOptions::controller chooses another
//   (i, pid); k is the estimate's order.
// - Outputs inside a step come from the pair's dense output mapped through
//   exp: R(t_n + theta h) = exp(hat(u(theta))) R_n, z(theta) likewise (one
//   exp each; DP853 needs its 3 extra stages once per step that holds an
//   output). Without a dense output (or with use_dense = false) steps are
//   clamped to land on every output time.
// - FSAL: the right-hand side at (t_n+1, z_n+1) is the next step's first
//   stage; the stage's dexpinv differs (u = 0 there), the evaluation not.
//
// Cost per accepted step: (stages - 1) rhs evaluations and dexpinv
// applications in each attempt, plus the FSAL stage's rhs where the error
// estimate does not use it, and one exp; each output adds one exp.
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"

namespace rb {

// RKMK on the tableau's embedded pair with a controller (a filter:
// integrators/controllers/), family "rkmk-adaptive". use_dense = false clamps
// steps onto the outputs even where the tableau has a dense output (for
// tests and comparisons). Throws InputError for a tableau without embedded
// weights or an unknown controller.
std::unique_ptr<Integrator> rkmk_adaptive(Tableau tableau, std::string name, const std::string& controller = "pi",
                                          bool use_dense = true);

}  // namespace rb

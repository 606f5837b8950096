#pragma once
// Adaptive explicit Runge-Kutta on the flat view y in R^14 with an embedded
// pair: the flat counterpart of rkmk_adaptive, with the same controller
// and the same kind of error norm, so that flat and Lie-group adaptivity
// compare on equal terms. R drifts off SO(3).
//
// - Local error h sum_i e_i k_i, each component against
//   atol + rtol max(|y_n,i|, |y_n+1,i|); norm: root mean square (Hairer's).
// - The step size comes from the shared controllers
//   (integrators/controllers/): Gustafsson's PI by default, as for
//   rkmk_adaptive; RunOptions::controller chooses another.
// - No dense output: steps are clamped to land on every output time.
// - FSAL where the tableau's error weights use its FSAL stage: the stage at
//   (t + h, y_new) starts the next step; otherwise F(y_new) is evaluated
//   after acceptance.
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"

namespace rb {

// Explicit RK on the tableau's embedded pair with a controller (a filter:
// integrators/controllers/), family "rk-adaptive". Throws InputError for a
// tableau without embedded weights (or with a stretched estimate, which only
// the Lie pairs combine) or an unknown controller.
std::unique_ptr<Integrator> rk_adaptive(Tableau tableau, std::string name, const std::string& controller = "pi");

}  // namespace rb

#pragma once
// Classical explicit Runge-Kutta on the flat view y in R^14 at fixed steps,
// for any tableau: the seminar's method. R drifts off SO(3). Its adaptive
// counterpart on an embedded pair is flat_embedded.hpp; registry lines name
// both through rk_method (tableau_methods.hpp).
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"

namespace rb {

// The fixed-step integrator of the tableau (family "rk"); name defaults to
// the tableau's name.
std::unique_ptr<Integrator> rk_fixed(Tableau tableau, std::string name = {});

}  // namespace rb

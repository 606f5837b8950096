#pragma once
// The integrators a tableau gives, by way of stepping and controller: a
// registry line names the three parts, e.g.
//   rkmk_method(methods::dormand_prince54(), "rkmk5", kConstantController)
//   rkmk_method(methods::dormand_prince54(), "rkmk-dp54-adaptive", "pi")
// - "constant": fixed steps of h with the tableau's propagating weights only
//   (stepped_method): no error estimate is computed;
// - a filter ("i", "pi", "pid"; integrators/controllers/): adaptive steps on
//   the tableau's embedded pair (adaptive_method),
//   with that filter as the method's default.
// Both ways step with the family's one stepper (families/rk/rk_stepper.hpp,
// families/rkmk/rkmk_stepper.hpp): the error estimate is computed only when
// a controller asks for it.
// The family says the way of stepping, with "-adaptive" for the pairs: rk,
// rk-adaptive, rkmk, rkmk-adaptive.
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"
#include "problems/so3.hpp"

namespace rb {

// Classical explicit RK on the flat view (family "rk", or "rk-adaptive"),
// both with the one stepper of families/rk/rk_stepper.hpp (made in
// families/rk/runge_kutta.cpp).
std::unique_ptr<Integrator> rk_method(Tableau tableau, std::string name, const std::string& controller);

// Runge-Kutta-Munthe-Kaas on the Lie-group view (family "rkmk", or
// "rkmk-adaptive"). A dexpinv other than the closed form (the truncated
// series, the seminar's) is a fixed-step variant only: InputError with a
// filter.
std::unique_ptr<Integrator> rkmk_method(Tableau tableau, std::string name, const std::string& controller,
                                        DexpinvKind dexpinv = DexpinvKind::exact);

// RKMK with the Cayley map for coordinates (family "rkmk"), fixed steps
// only: InputError with a filter.
std::unique_ptr<Integrator> rkmk_cayley_method(Tableau tableau, std::string name, const std::string& controller);

// What every adaptive method on a tableau needs before it is built: a known
// filter controller and embedded weights to estimate its error with. Throws
// InputError otherwise.
void require_embedded_pair(const Tableau& tableau, const std::string& controller);

}  // namespace rb

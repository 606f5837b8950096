#pragma once
// The suite's symmetric implicit methods (docs/model.md, "Symmetric implicit
// methods"), each solved by the simplified Newton of newton.hpp with the AD
// Jacobian:
// - gauss2, gauss4, gauss6: Gauss-Legendre collocation with 1, 2, 3 stages
//   on the flat view (family "gauss"); gauss2 is the implicit midpoint rule;
// - gauss2-tj4, gauss2-tj6: gauss2 composed by the triple jump (flat);
// - lie-gauss2: the Lie midpoint rule on SO(3) x R^5, theta = h xi(exp(theta
//   / 2) y0), y1 = exp(theta) y0 (family "lie-gauss"), and lie-gauss2-tj4,
//   lie-gauss2-tj6, its triple-jump compositions: each the Lie-group twin of
//   the flat method of the same tableau name.
//
// Each way of stepping is fixed-step only (InputError, key "controller", for
// any controller but "constant") and refuses method data it has no method
// for (InputError, key "integrator").
#include <memory>
#include <string>

#include "integrators/integrator.hpp"

namespace rb {

// Gauss collocation with 1, 2 or 3 stages on the flat view, called name.
std::unique_ptr<Integrator> gauss_method(int stages, std::string name, const std::string& controller);

// The implicit midpoint rule (order 2: gauss_method with 1 stage) or its
// triple-jump composition of order 4 or 6 on the flat view, called name.
std::unique_ptr<Integrator> midpoint_composition(int order, std::string name, const std::string& controller);

// The Lie midpoint rule (order 2) or its triple-jump composition of order 4
// or 6 on the Lie-group view, called name.
std::unique_ptr<Integrator> lie_midpoint_composition(int order, std::string name, const std::string& controller);

}  // namespace rb

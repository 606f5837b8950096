// The discrete-gradient method: energy conserved to rounding.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/discrete_gradient/discrete_gradient.hpp"
#include "integrators/families/families.hpp"

namespace rb {

void register_discrete_gradient(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md).
  const std::string constant = kConstantController;
  list.push_back(discrete_gradient_method(DiscreteGradient::gonzalez_midpoint, "dg2", constant));
}

}  // namespace rb

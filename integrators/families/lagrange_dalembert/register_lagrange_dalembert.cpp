// The discrete Lagrange-d'Alembert method: variational, symmetric, on
// SO(3) x R^2.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/families.hpp"
#include "integrators/families/lagrange_dalembert/lagrange_dalembert.hpp"

namespace rb {

void register_lagrange_dalembert(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md).
  const std::string constant = kConstantController;
  list.push_back(lagrange_dalembert_method(DiscreteConstraint::trapezoidal, "dla2", constant));
}

}  // namespace rb

// Symmetric implicit methods, solved by the suite's simplified Newton
// (integrators/steppers/newton.hpp): flat Gauss collocation, and the implicit
// midpoint rule composed to orders 4 and 6, flat and on the group.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/families.hpp"
#include "integrators/families/symmetric/gauss.hpp"

namespace rb {

void register_symmetric(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md); the data is a stage count or a composed order.
  const std::string constant = kConstantController;
  list.push_back(gauss_method(1, "gauss2", constant));
  list.push_back(gauss_method(2, "gauss4", constant));
  list.push_back(gauss_method(3, "gauss6", constant));
  list.push_back(midpoint_composition(4, "gauss2-tj4", constant));
  list.push_back(midpoint_composition(6, "gauss2-tj6", constant));
  list.push_back(lie_midpoint_composition(2, "lie-gauss2", constant));
  list.push_back(lie_midpoint_composition(4, "lie-gauss2-tj4", constant));
  list.push_back(lie_midpoint_composition(6, "lie-gauss2-tj6", constant));
}

}  // namespace rb

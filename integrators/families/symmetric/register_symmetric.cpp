// Symmetric implicit methods, solved by the suite's simplified Newton
// (integrators/steppers/newton.hpp): flat Gauss collocation, and the implicit
// midpoint rule composed to orders 4 and 6, flat and on the group.
#include "integrators/families/families.hpp"
#include "integrators/families/symmetric/gauss.hpp"

namespace rb {

void register_symmetric(MethodList& list) {
  for (const int stages : {1, 2, 3}) list.push_back(gauss_method(stages));
  for (const int order : {4, 6}) list.push_back(midpoint_composition(order, false));
  for (const int order : {2, 4, 6}) list.push_back(midpoint_composition(order, true));
}

}  // namespace rb

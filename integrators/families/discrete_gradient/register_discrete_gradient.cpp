// The discrete-gradient method: energy conserved to rounding.
#include "integrators/families/discrete_gradient/discrete_gradient.hpp"
#include "integrators/families/families.hpp"

namespace rb {

void register_discrete_gradient(MethodList& list) { list.push_back(discrete_gradient_method()); }

}  // namespace rb

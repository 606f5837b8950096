// The discrete Lagrange-d'Alembert method: variational, symmetric, on
// SO(3) x R^2.
#include "integrators/families/families.hpp"
#include "integrators/families/lagrange_dalembert/lagrange_dalembert.hpp"

namespace rb {

void register_lagrange_dalembert(MethodList& list) { list.push_back(lagrange_dalembert_method()); }

}  // namespace rb

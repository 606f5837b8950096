#include "integrators/families/families.hpp"

namespace rb {

// Every family, one line each, in the order `rollbench list` shows them:
// FAMILY(x) is the folder integrators/families/x/, which defines
// register_x(MethodList&).
#define RB_FAMILIES(FAMILY)  \
  FAMILY(rk)                 \
  FAMILY(rkmk)               \
  FAMILY(baselines)          \
  FAMILY(exp_product)        \
  FAMILY(symmetric)          \
  FAMILY(discrete_gradient)  \
  FAMILY(lagrange_dalembert) \
  FAMILY(odeint)             \
  FAMILY(gsl)

#define RB_DECLARE_FAMILY(x) void register_##x(MethodList&);
RB_FAMILIES(RB_DECLARE_FAMILY)
#define RB_FAMILY_FUNCTION(x) register_##x,

MethodList methods_of(std::initializer_list<RegisterFamily> families) {
  MethodList methods;
  for (const RegisterFamily add_family : families) add_family(methods);
  return methods;
}

MethodList builtin_methods() { return methods_of({RB_FAMILIES(RB_FAMILY_FUNCTION)}); }

}  // namespace rb

// GSL odeiv2's steppers on the flat view.
#include "integrators/families/families.hpp"
#include "integrators/families/gsl/gsl.hpp"

namespace rb {

void register_gsl(MethodList& list) {
  // fixed step: the one-step methods. msadams, msbdf and bsimp choose their
  // order from a tolerance, so they run adaptive only; rk8pd too, since at
  // fixed steps its error falls from 1e-3 to rounding within three halvings
  // of h, too few for the order test to see order 8
  for (const char* stepper : {"rk2", "rk4", "rkf45", "rkck", "rk1imp", "rk2imp", "rk4imp"})
    list.push_back(gsl_method(stepper, GslDrive::fixed_step));
  for (const char* stepper : {"rk2", "rkf45", "rkck", "rk8pd", "rk4imp", "bsimp", "msadams", "msbdf"})
    list.push_back(gsl_method(stepper, GslDrive::adaptive));
}

}  // namespace rb

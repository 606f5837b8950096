// GSL odeiv2's steppers on the flat view.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/families.hpp"
#include "integrators/families/gsl/gsl.hpp"

namespace rb {

void register_gsl(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md); the data is GSL's stepper name, "library" GSL's
  // own control.
  const std::string constant = kConstantController, library = kLibraryController;
  // fixed step: the one-step methods. msadams, msbdf and bsimp choose their
  // order from a tolerance, so they run adaptive only; rk8pd too, since at
  // fixed steps its error falls from 1e-3 to rounding within three halvings
  // of h, too few for the order test to see order 8
  list.push_back(gsl_method("rk2", "gsl-rk2", constant));
  list.push_back(gsl_method("rk4", "gsl-rk4", constant));
  list.push_back(gsl_method("rkf45", "gsl-rkf45", constant));
  list.push_back(gsl_method("rkck", "gsl-rkck", constant));
  list.push_back(gsl_method("rk1imp", "gsl-rk1imp", constant));
  list.push_back(gsl_method("rk2imp", "gsl-rk2imp", constant));
  list.push_back(gsl_method("rk4imp", "gsl-rk4imp", constant));
  list.push_back(gsl_method("rk2", "gsl-rk2-adaptive", library));
  list.push_back(gsl_method("rkf45", "gsl-rkf45-adaptive", library));
  list.push_back(gsl_method("rkck", "gsl-rkck-adaptive", library));
  list.push_back(gsl_method("rk8pd", "gsl-rk8pd-adaptive", library));
  list.push_back(gsl_method("rk4imp", "gsl-rk4imp-adaptive", library));
  list.push_back(gsl_method("bsimp", "gsl-bsimp-adaptive", library));
  list.push_back(gsl_method("msadams", "gsl-msadams-adaptive", library));
  list.push_back(gsl_method("msbdf", "gsl-msbdf-adaptive", library));
}

}  // namespace rb

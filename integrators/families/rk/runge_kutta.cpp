// The rk family's integrators: classical explicit RK on the flat view at
// fixed steps (family "rk") and on a tableau's embedded pair (family
// "rk-adaptive"), both with the one stepper of rk_stepper.hpp.
#include <string>
#include <utility>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/rk/rk_stepper.hpp"
#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

MethodInfo fixed_facts(const Tableau& t, std::string name) {
  return {.name = std::move(name),
          .family = "rk",
          .declared_order = t.order(),
          .description = "classical explicit RK (" + t.name() + " tableau, " + std::to_string(t.stages()) +
                         (t.stages() == 1 ? " stage" : " stages") + ") on the flat view",
          .tableau = t.name()};
}

MethodInfo adaptive_facts(const Tableau& t, std::string name, const std::string& controller) {
  return {.name = std::move(name),
          .family = "rk-adaptive",
          .declared_order = t.order(),
          .embedded_order = t.embedded_order(),
          .controller = controller,
          .description = "adaptive explicit RK on the " + t.name() + " pair (order " + std::to_string(t.order()) +
                         ", " + std::to_string(t.attempt_stages()) + " stages" + (t.fsal_in_attempt() ? ", FSAL" : "") +
                         ", " + controller_title(controller) + " controller by default) on the flat view; steps " +
                         "clamped onto the outputs",
          .tableau = t.name()};
}

}  // namespace

std::unique_ptr<Integrator> rk_method(Tableau tableau, std::string name, const std::string& controller) {
  if (controller == kConstantController) {
    MethodInfo info = fixed_facts(tableau, std::move(name));
    return stepped_method(std::move(info), [tableau = std::move(tableau)](const Problem& problem, auto&& drive) {
      return with_rk_stepper<false>(problem, tableau, Tolerances(), drive);
    });
  }
  require_embedded_pair(tableau, controller);
  // the flat error norm is the plain one
  if (!tableau.e_stretched().empty())
    throw InputError(
        "tableau '" + tableau.name() + "' has a stretched error estimate, which the flat pair does not combine",
        "e_stretched");
  MethodInfo info = adaptive_facts(tableau, std::move(name), controller);
  return adaptive_method(std::move(info), [tableau = std::move(tableau)](const Problem& problem, const RunOptions&,
                                                                         const Tolerances& tol, auto&& drive) {
    return with_rk_stepper<true>(problem, tableau, tol, drive);
  });
}

}  // namespace rb

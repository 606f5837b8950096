#include "integrators/steppers/tableau_methods.hpp"

#include "integrators/controllers/controller.hpp"
#include "integrators/families/rkmk/munthe_kaas.hpp"
#include "integrators/families/rkmk/munthe_kaas_adaptive.hpp"
#include "problems/input_error.hpp"

namespace rb {

void require_embedded_pair(const Tableau& tableau, const std::string& controller) {
  (void)filter_controller(controller);  // throws for an unknown one
  if (!tableau.has_error_estimate())
    throw InputError("tableau '" + tableau.name() + "' has no embedded weights for an adaptive method", "e");
}

std::unique_ptr<Integrator> rkmk_method(Tableau tableau, std::string name, const std::string& controller,
                                        DexpinvKind dexpinv) {
  if (controller == kConstantController) return rkmk_fixed(std::move(tableau), std::move(name), dexpinv);
  if (dexpinv != DexpinvKind::exact)
    throw InputError("'" + name + "': only the closed-form dexpinv has an adaptive RKMK", "controller");
  return rkmk_adaptive(std::move(tableau), std::move(name), controller);
}

std::unique_ptr<Integrator> rkmk_cayley_method(Tableau tableau, std::string name, const std::string& controller) {
  if (controller != kConstantController)
    throw InputError("'" + name + "': RKMK with the Cayley map runs at fixed steps only", "controller");
  return rkmk_cayley_fixed(std::move(tableau), std::move(name));
}

}  // namespace rb

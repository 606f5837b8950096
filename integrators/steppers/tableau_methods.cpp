#include "integrators/steppers/tableau_methods.hpp"

#include "integrators/controllers/controller.hpp"
#include "integrators/families/rkmk/munthe_kaas.hpp"
#include "problems/input_error.hpp"

namespace rb {

void require_embedded_pair(const Tableau& tableau, const std::string& controller) {
  (void)filter_controller(controller);  // throws for an unknown one
  if (!tableau.has_error_estimate())
    throw InputError("tableau '" + tableau.name() + "' has no embedded weights for an adaptive method", "e");
}

std::unique_ptr<Integrator> rkmk_method(Tableau tableau, std::string name, const std::string& controller,
                                        DexpinvKind dexpinv) {
  return rkmk_integrator(std::move(tableau), std::move(name), controller, dexpinv);
}

std::unique_ptr<Integrator> rkmk_cayley_method(Tableau tableau, std::string name, const std::string& controller) {
  return rkmk_cayley_integrator(std::move(tableau), std::move(name), controller);
}

}  // namespace rb

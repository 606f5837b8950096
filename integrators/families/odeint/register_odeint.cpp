// Boost.Odeint's steppers on the flat view.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/families.hpp"
#include "integrators/families/odeint/odeint.hpp"

namespace rb {

void register_odeint(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md); "library": odeint's own controller.
  using S = OdeintStepper;
  const std::string constant = kConstantController, library = kLibraryController;
  list.push_back(odeint_method(S::euler, "odeint-euler", constant));
  list.push_back(odeint_method(S::rk4, "odeint-rk4", constant));
  list.push_back(odeint_method(S::cash_karp54, "odeint-cash-karp54", constant));
  list.push_back(odeint_method(S::dopri5, "odeint-dopri5", constant));
  list.push_back(odeint_method(S::fehlberg78, "odeint-fehlberg78", constant));
  list.push_back(odeint_method(S::abm4, "odeint-abm4", constant));
  list.push_back(odeint_method(S::abm5, "odeint-abm5", constant));
  list.push_back(odeint_method(S::dopri5, "odeint-dopri5-adaptive", library));
  list.push_back(odeint_method(S::cash_karp54, "odeint-cash-karp54-adaptive", library));
  list.push_back(odeint_method(S::fehlberg78, "odeint-fehlberg78-adaptive", library));
  list.push_back(odeint_method(S::bulirsch_stoer, "odeint-bulirsch-stoer", library));
}

}  // namespace rb

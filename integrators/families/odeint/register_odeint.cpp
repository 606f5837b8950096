// Boost.Odeint's steppers on the flat view.
#include "integrators/families/families.hpp"
#include "integrators/families/odeint/odeint.hpp"

namespace rb {

void register_odeint(MethodList& list) {
  list.push_back(odeint_euler());
  list.push_back(odeint_rk4());
  list.push_back(odeint_cash_karp54());
  list.push_back(odeint_dopri5());
  list.push_back(odeint_fehlberg78());
  list.push_back(odeint_abm4());
  list.push_back(odeint_abm5());
  list.push_back(odeint_dopri5_adaptive());
  list.push_back(odeint_cash_karp54_adaptive());
  list.push_back(odeint_fehlberg78_adaptive());
  list.push_back(odeint_bulirsch_stoer());
}

}  // namespace rb

#include "integrators/user_tableaux.hpp"

#include "integrators/steppers/flat_embedded.hpp"
#include "integrators/steppers/munthe_kaas.hpp"
#include "integrators/steppers/munthe_kaas_adaptive.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/runge_kutta.hpp"
#include "problems/input_error.hpp"

namespace rb {

std::vector<std::unique_ptr<Integrator>> integrators_of(const TableauFile& file) {
  const Tableau& t = file.tableau;
  const std::string& name = t.name();
  // at fixed steps only the stages b weights are evaluated (a pair's FSAL
  // stage is not); the adaptive variants use the embedded weights
  std::vector<std::unique_ptr<Integrator>> made;
  made.push_back(std::make_unique<RungeKutta>(t, "rk-" + name));
  made.push_back(std::make_unique<MuntheKaas>(t, "rkmk-" + name));
  if (t.has_error_estimate()) {
    made.push_back(std::make_unique<RungeKuttaAdaptive>(t, "rk-" + name + "-adaptive"));
    made.push_back(std::make_unique<MuntheKaasAdaptive>(t, "rkmk-" + name + "-adaptive"));
  }
  return made;
}

std::vector<std::string> register_tableau_file(const std::string& path) {
  std::vector<std::unique_ptr<Integrator>> made = integrators_of(load_tableau_file(path));
  std::vector<std::string> names;
  // all names checked before any is added: a clash leaves the registry as it was
  for (const auto& integrator : made) {
    for (const auto& existing : registry())
      if (existing->name() == integrator->name())
        throw InputError("tableau file '" + path + "': 'name': integrator '" + integrator->name() +
                         "' is already registered; rename the tableau");
    names.push_back(integrator->name());
  }
  for (auto& integrator : made) add_integrator(std::move(integrator), "tableau");
  return names;
}

}  // namespace rb

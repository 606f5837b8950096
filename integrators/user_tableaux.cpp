#include "integrators/user_tableaux.hpp"

#include "integrators/controllers/controller.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "integrators/tableau_twins.hpp"
#include "problems/input_error.hpp"

namespace rb {

std::vector<std::unique_ptr<Integrator>> integrators_of(const TableauFile& file) {
  const Tableau& t = file.tableau;
  const std::string& name = t.name();
  // at fixed steps only the stages b weights are evaluated (a pair's FSAL
  // stage is not); the adaptive variants use the embedded weights
  std::vector<std::unique_ptr<Integrator>> made;
  made.push_back(rk_method(t, "rk-" + name, kConstantController));
  made.push_back(rkmk_method(t, "rkmk-" + name, kConstantController));
  if (t.has_error_estimate()) {
    made.push_back(rk_method(t, "rk-" + name + "-adaptive", "pi"));
    made.push_back(rkmk_method(t, "rkmk-" + name + "-adaptive", "pi"));
  }
  return made;
}

std::vector<std::string> register_tableau_file(const std::string& path, std::string* note) {
  const TableauFile file = load_tableau_file(path);
  if (note) {
    const std::optional<std::string> twin = shipped_twin(file.tableau);
    *note = twin ? "tableau file '" + path + "': tableau '" + file.tableau.name() + "' has the A, b and c of " + *twin +
                       ": the same method under another name"
                 : std::string();
  }
  std::vector<std::unique_ptr<Integrator>> made = integrators_of(file);
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

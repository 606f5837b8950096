#include "integrators/user_tableaux.hpp"

#include <algorithm>

#include "integrators/steppers/flat_embedded.hpp"
#include "integrators/steppers/munthe_kaas.hpp"
#include "integrators/steppers/munthe_kaas_adaptive.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/runge_kutta.hpp"
#include "problems/input_error.hpp"

namespace rb {

EmbeddedPair embedded_pair_of(const TableauFile& file) {
  const Tableau& t = file.tableau;
  const int s = t.stages();
  EmbeddedPair p;
  p.name = t.name();
  p.order = t.order();
  // b - b_err estimates the error of the lower-order member: O(h^(min + 1))
  p.error_order = std::min(t.order(), file.err_order) + 1;
  p.stages = p.total = s;
  for (int i = 0; i < s; ++i) {
    p.c.push_back(t.c(i));
    p.b.push_back(t.b(i));
    p.e.push_back(t.b(i) - file.b_err[static_cast<std::size_t>(i)]);
    for (int j = 0; j < s; ++j) p.a.push_back(t.a(i, j));
  }
  // first same as last: the last stage is evaluated at (t + h, y_new)
  bool fsal = s >= 2 && t.c(s - 1) == 1.0 && t.b(s - 1) == 0.0;
  for (int j = 0; j < s && fsal; ++j) fsal = t.a(s - 1, j) == t.b(j);
  p.fsal = fsal ? s - 1 : s;
  return p;
}

std::vector<std::unique_ptr<Integrator>> integrators_of(const TableauFile& file) {
  const std::string& name = file.tableau.name();
  std::vector<std::unique_ptr<Integrator>> made;
  if (file.b_err.empty()) {
    made.push_back(std::make_unique<RungeKutta>(file.tableau, "rk-" + name));
    made.push_back(std::make_unique<MuntheKaas>(file.tableau, "rkmk-" + name));
  } else {
    // at fixed steps a pair's stages after the last non-zero b (its FSAL
    // stage) are never used: the propagating tableau leaves them out
    const EmbeddedPair pair = embedded_pair_of(file);
    made.push_back(std::make_unique<RungeKutta>(pair.tableau(name), "rk-" + name));
    made.push_back(std::make_unique<MuntheKaas>(pair.tableau(name), "rkmk-" + name));
    made.push_back(std::make_unique<RungeKuttaAdaptive>(pair, "rk-" + name + "-adaptive"));
    made.push_back(std::make_unique<MuntheKaasAdaptive>(pair, "rkmk-" + name + "-adaptive"));
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

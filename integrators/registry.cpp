#include "integrators/registry.hpp"

#include "integrators/families/families.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

std::vector<std::unique_ptr<Integrator>>& mutable_registry() {
  static std::vector<std::unique_ptr<Integrator>> all = builtin_methods();
  return all;
}

}  // namespace

const std::vector<std::unique_ptr<Integrator>>& registry() { return mutable_registry(); }

void add_integrator(std::unique_ptr<Integrator> integrator, const std::string& key) {
  for (const auto& existing : registry())
    if (existing->name() == integrator->name())
      throw InputError("integrator '" + integrator->name() + "' is already registered", key);
  mutable_registry().push_back(std::move(integrator));
}

const Integrator& find_integrator(std::string_view name) {
  for (const auto& integrator : registry())
    if (integrator->name() == name) return *integrator;
  throw InputError("unknown integrator '" + std::string(name) + "' (`rollbench list` shows them all)", "integrator");
}

}  // namespace rb

#include "bench/lib/stepper_option.hpp"

#include "integrators/steppers/plugin_stepper.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"

namespace rb {

void register_plugin_steppers(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    std::unique_ptr<Integrator> stepper = load_plugin_stepper(path);
    try {
      add_integrator(std::move(stepper), "stepper");
    } catch (const InputError& e) {
      // the registry's sentence, with the file it came from
      throw InputError("'" + path + "': rollbench_stepper_info(): " + e.message(), "stepper");
    }
  }
}

}  // namespace rb

#include "bench/lib/stepper_option.hpp"

#include <cmath>

#include "integrators/registry.hpp"
#include "integrators/steppers/plugin_stepper.hpp"
#include "problems/input_error.hpp"

namespace rb {

PluginIsolation plugin_isolation(const std::string& mode, double wall_limit_s) {
  PluginIsolation isolation;
  if (mode == "none") {
    isolation.mode = PluginIsolation::Mode::none;
  } else if (!mode.empty() && mode != "process") {
    throw InputError("expected process (each plug-in run in a child process) or none (in-process), got '" + mode + "'",
                     "stepper-isolation");
  }
  if (!std::isnan(wall_limit_s)) {
    if (!(wall_limit_s > 0.0 && std::isfinite(wall_limit_s)))
      throw InputError("the wall-clock limit of a plug-in run must be a finite number of seconds > 0",
                       "stepper-timeout");
    isolation.wall_limit_s = wall_limit_s;
  }
  return isolation;
}

void register_plugin_steppers(const std::vector<std::string>& paths, const PluginIsolation& isolation) {
  for (const std::string& path : paths) {
    std::unique_ptr<Integrator> stepper = load_plugin_stepper(path, isolation);
    try {
      add_integrator(std::move(stepper), "stepper");
    } catch (const InputError& e) {
      // the registry's sentence, with the file it came from
      throw InputError("'" + path + "': rollbench_stepper_info(): " + e.message(), "stepper");
    }
  }
}

}  // namespace rb

#pragma once
// The --stepper option of `rollbench run`, `trajectory` and `list`: each
// path is a stepper library (integrators/plugin/rollbench_stepper.h),
// loaded and registered after the built-in methods before anything runs.
#include <string>
#include <vector>

#include "integrators/steppers/plugin_stepper.hpp"

namespace rb {

// --stepper-isolation (process | none) and --stepper-timeout SECONDS as
// given (empty, NaN: not given), checked: InputError under the option's
// name for another word or a limit that is not a finite number > 0.
PluginIsolation plugin_isolation(const std::string& mode, double wall_limit_s);

// Loads and registers every library in paths, in order. Throws InputError
// (key "stepper") naming the file and what is wrong: a missing file, not a
// shared library, a missing symbol, another ABI version, bad facts, or a
// name the registry already has.
// Each runs as isolation says.
void register_plugin_steppers(const std::vector<std::string>& paths, const PluginIsolation& isolation = {});

}  // namespace rb

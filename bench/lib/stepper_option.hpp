#pragma once
// The --stepper option of `rollbench run`, `trajectory` and `list`: each
// path is a stepper library (integrators/plugin/rollbench_stepper.h),
// loaded and registered after the built-in methods before anything runs.
#include <string>
#include <vector>

namespace rb {

// Loads and registers every library in paths, in order. Throws InputError
// (key "stepper") naming the file and what is wrong: a missing file, not a
// shared library, a missing symbol, another ABI version, bad facts, or a
// name the registry already has.
void register_plugin_steppers(const std::vector<std::string>& paths);

}  // namespace rb

#pragma once
// Steppers from outside the suite: a shared library built against
// integrators/plugin/rollbench_stepper.h, loaded with dlopen when the user
// names it (--stepper PATH.so) and driven by drive_fixed_step like a
// built-in fixed-step method: the same right-hand side (the Problem's flat
// and Lie-group views, through C callbacks that count into Cost), the same
// validity checks after every step, failures as statuses.
#include <memory>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/plugin/rollbench_stepper.h"

namespace rb {

// What the callbacks of one run evaluate and count into: the problem and
// the run's own Cost (one per run, so runs on many threads do not share it).
struct PluginCallContext {
  const Problem* problem;
  Cost* cost;
};

// The callback table of the ABI over context (which must outlive its use).
rollbench_problem plugin_callbacks(PluginCallContext& context);

// Loads the stepper library at path and checks it: the file exists and is a
// shared object, it exports the three symbols, its ABI version is this
// suite's, and its facts are sound (a name of letters, digits and . _ + -,
// a family, order >= 1, a view). Throws InputError under key "stepper"
// naming the file and the symbol otherwise. The library stays loaded for
// the life of the process (the integrator is in the registry until then).
std::unique_ptr<Integrator> load_plugin_stepper(const std::string& path);

}  // namespace rb

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
#include "integrators/steppers/isolated_run.hpp"

namespace rb {

// How a plug-in's runs are kept from taking the process down
// (docs/design.md, "Plug-in isolation"): each run in a child process
// (process, the default) or in the caller's thread (none).
struct PluginIsolation {
  enum class Mode { process, none };
  Mode mode = Mode::process;
  double wall_limit_s = kDefaultIsolatedWallLimit;  // process only: the limit of one run
};

// The largest ||R^T R - I||_F a Lie-view plug-in may return: a step that
// returns more ends the run with the status "off-group". Products of
// exponentials stay on SO(3) to rounding: at a few eps a step, even 10^8
// steps (the budget of `trajectory`) add up to less than 1e-7, so a state
// beyond 1e-6 was not made by a method that keeps R on the group.
inline constexpr double kOffGroupBound = 1e-6;

// What the callbacks of one run evaluate and count into: the problem and
// the run's own Cost (one per run, so runs on many threads do not share it).
struct PluginCallContext {
  const Problem* problem;
  Cost* cost;
};

// The callback table of the ABI over context (which must outlive its use).
rollbench_problem plugin_callbacks(PluginCallContext& context);

// Loads the stepper library at path and checks it: the path is a file (a
// folder is named as one) and a shared object, it exports the three symbols, its ABI version is this
// suite's, and its facts are sound (a name of letters, digits and . _ + -,
// a family, order >= 1, a view). Throws InputError under key "stepper"
// naming the file and the symbol otherwise. The library stays loaded for
// the life of the process (the integrator is in the registry until then).
// The description and family are made valid UTF-8 (problems/utf8.hpp).
std::unique_ptr<Integrator> load_plugin_stepper(const std::string& path, const PluginIsolation& isolation = {});

}  // namespace rb

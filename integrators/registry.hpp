#pragma once
// The one list of methods: name -> integrator. The runner, the CLI, the
// reports and the conformance tests read it; nothing else lists methods.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

// Every registered integrator, in registration order.
const std::vector<std::unique_ptr<Integrator>>& registry();

// The integrator called name; throws InputError (key "integrator") naming it
// when there is none.
const Integrator& find_integrator(std::string_view name);

// Adds an integrator made at run time (from a --tableau file or a --stepper
// plug-in) after the built-in ones, so that everything reading the registry
// sees it like any other. Call it before runs start: the registry is not
// locked. Throws InputError under key when the name is already taken.
void add_integrator(std::unique_ptr<Integrator> integrator, const std::string& key);

}  // namespace rb

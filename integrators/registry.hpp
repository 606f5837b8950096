#pragma once
// The one list of methods: name -> integrator. The runner, the CLI, the
// reports and the conformance tests read it; nothing else lists methods.
#include <memory>
#include <string_view>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

// Every registered integrator, in registration order.
const std::vector<std::unique_ptr<Integrator>>& registry();

// The integrator called name; throws InputError (key "integrator") naming it
// when there is none.
const Integrator& find_integrator(std::string_view name);

}  // namespace rb

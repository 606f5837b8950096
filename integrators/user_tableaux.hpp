#pragma once
// The integrators one tableau file gives (docs/formats.md, "Butcher tableau"):
// rk-<name> on the flat view and rkmk-<name> on the Lie-group view; with
// b_err also rk-<name>-adaptive and rkmk-<name>-adaptive on the embedded
// pair (PI controller, steps clamped onto the outputs).
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "integrators/tableau_file.hpp"

namespace rb {

// The file's integrators, in the order rk-, rkmk-, rk-...-adaptive, rkmk-...-adaptive.
std::vector<std::unique_ptr<Integrator>> integrators_of(const TableauFile& file);

// Loads the tableau file at path and adds its integrators to the registry
// (after the built-in ones); returns their names. Throws InputError naming
// the file when it is not a valid tableau or when one of the names is taken
// (then none is added). Where the file's method is a shipped one
// (tableau_twins.hpp), note gets a line saying so; empty otherwise.
std::vector<std::string> register_tableau_file(const std::string& path, std::string* note = nullptr);

}  // namespace rb

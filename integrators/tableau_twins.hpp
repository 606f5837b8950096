#pragma once
// Whether a tableau is one the suite ships (docs/formats.md, "Butcher
// tableau"): a file that types in Kutta's 3/8 rule adds rk-<name> and
// rkmk-<name>, which step exactly as rk38 and its Lie twin; a note says so,
// so that a comparison does not count one method twice unawares.
#include <optional>
#include <string>

#include "integrators/tableau.hpp"

namespace rb {

// The shipped tableau whose propagated method (A, b, c, to kTwinTolerance)
// a tableau's equals, with its source and the built-in integrator that steps
// with it: "the shipped tableau 'rk38' (Kutta (1901), the 3/8 rule; built
// in as rk38)"; none where no shipped tableau has those coefficients.
std::optional<std::string> shipped_twin(const Tableau& tableau);

// Coefficients printed to 16 digits agree with the exact ones to ~1e-16.
inline constexpr double kTwinTolerance = 1e-13;

}  // namespace rb

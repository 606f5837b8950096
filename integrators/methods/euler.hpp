#pragma once
// Source: Euler (1768).
#include "integrators/tableau.hpp"

namespace rb::tableaus {

inline Tableau euler() { return Tableau("euler", 1, {0.0}, {1.0}, {0.0}); }

}  // namespace rb::tableaus

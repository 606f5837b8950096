#pragma once
// Source: Euler (1768).
#include "integrators/tableau.hpp"

namespace rb::methods {

inline Tableau euler() { return Tableau("euler", 1, {0.0}, {1.0}, {0.0}, "Euler (1768)"); }

}  // namespace rb::methods

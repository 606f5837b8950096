#pragma once
// Source: Heun (1900), the explicit trapezoidal rule.
#include "integrators/tableau.hpp"

// the coefficients keep the layout of their tables
// clang-format off
namespace rb::methods {

inline Tableau heun() { return Tableau("heun", 2, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1}, "Heun (1900), the explicit trapezoidal rule"); }

}  // namespace rb::methods
// clang-format on

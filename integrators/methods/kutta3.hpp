#pragma once
// Source: Kutta (1901).
#include "integrators/tableau.hpp"

namespace rb::methods {

// Kutta's third-order method.
inline Tableau kutta3() {
  return Tableau("rk3", 3, {0, 0, 0, 0.5, 0, 0, -1, 2, 0}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {0, 0.5, 1}, "Kutta (1901)");
}

}  // namespace rb::methods

#pragma once
// Source: Kutta (1901), the classical fourth-order method.
#include "integrators/tableau.hpp"

namespace rb::methods {

inline Tableau rk4() {
  return Tableau("rk4", 4, {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0}, {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6},
                 {0, 0.5, 0.5, 1}, "Kutta (1901), the classical fourth-order method");
}

}  // namespace rb::methods

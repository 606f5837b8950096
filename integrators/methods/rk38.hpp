#pragma once
// Source: Kutta (1901), the 3/8 rule.
#include "integrators/tableau.hpp"

namespace rb::methods {

// Kutta's 3/8 rule.
inline Tableau rk38() {
  return Tableau("rk38", 4, {0, 0, 0, 0, 1.0 / 3, 0, 0, 0, -1.0 / 3, 1, 0, 0, 1, -1, 1, 0},
                 {1.0 / 8, 3.0 / 8, 3.0 / 8, 1.0 / 8}, {0, 1.0 / 3, 2.0 / 3, 1}, "Kutta (1901), the 3/8 rule");
}

}  // namespace rb::methods

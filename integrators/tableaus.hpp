#pragma once
// The named classical tableaus. Adding one is a function here plus a
// registry line.
#include "integrators/tableau.hpp"

namespace rb::tableaus {

inline Tableau euler() { return Tableau("euler", 1, {0.0}, {1.0}, {0.0}); }

inline Tableau heun() { return Tableau("heun", 2, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1}); }

// Kutta's third-order method.
inline Tableau kutta3() {
  return Tableau("rk3", 3, {0, 0, 0, 0.5, 0, 0, -1, 2, 0}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {0, 0.5, 1});
}

inline Tableau rk4() {
  return Tableau("rk4", 4, {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0}, {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6},
                 {0, 0.5, 0.5, 1});
}

// Kutta's 3/8 rule.
inline Tableau rk38() {
  return Tableau("rk38", 4, {0, 0, 0, 0, 1.0 / 3, 0, 0, 0, -1.0 / 3, 1, 0, 0, 1, -1, 1, 0},
                 {1.0 / 8, 3.0 / 8, 3.0 / 8, 1.0 / 8}, {0, 1.0 / 3, 2.0 / 3, 1});
}

}  // namespace rb::tableaus

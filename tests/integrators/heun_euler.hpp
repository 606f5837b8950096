#pragma once
// Heun's method with Euler embedded, a 2-stage pair no registry entry uses:
// the tests' own small tableau with an error estimate.
#include <utility>

#include "integrators/tableau.hpp"

namespace rb::testing {

// e = b - b_hat with b_hat = (1, 0), Euler.
inline Tableau heun_euler() {
  TableauCoefficients k;
  k.name = "heun-euler";
  k.order = 2;
  k.a = {0, 0, 1, 0};
  k.b = {0.5, 0.5};
  k.c = {0, 1};
  k.e = {-0.5, 0.5};
  k.embedded_order = 1;
  k.source = "Heun (1900), Euler embedded";
  return Tableau(std::move(k));
}

}  // namespace rb::testing

#pragma once
// Source: Bogacki & Shampine, A 3(2) pair of Runge-Kutta formulas, Appl. Math. Lett. 2 (1989).
#include "integrators/tableau.hpp"

namespace rb::methods {

// Bogacki-Shampine 3(2): FSAL, its error weights use the FSAL stage (3 new
// stages an attempt); the dense output is the cubic Hermite interpolant
// (3rd order) through both ends' derivatives.
inline Tableau bogacki_shampine32() {
  TableauCoefficients p;
  p.name = "bs32";
  p.order = 3;
  p.a = {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.75, 0, 0, 2.0 / 9, 1.0 / 3, 4.0 / 9, 0};
  p.b = {2.0 / 9, 1.0 / 3, 4.0 / 9, 0};
  p.c = {0, 0.5, 0.75, 1};
  p.e = {5.0 / 72, -1.0 / 12, -1.0 / 9, 1.0 / 8};
  p.embedded_order = 2;
  p.dense = {1, -4.0 / 3, 5.0 / 9, 0, 1, -2.0 / 3, 0, 4.0 / 3, -8.0 / 9, 0, -1, 1};
  p.dense_order = 3;
  p.dense_degree = 3;
  p.source = "Bogacki & Shampine, A 3(2) pair of Runge-Kutta formulas, Appl. Math. Lett. 2 (1989)";
  return Tableau(std::move(p));
}

}  // namespace rb::methods

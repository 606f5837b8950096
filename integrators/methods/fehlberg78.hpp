#pragma once
// Source: Fehlberg (1968), NASA TR R-287, as in Boost.Odeint's runge_kutta_fehlberg78.
#include "integrators/methods/coefficients.hpp"
#include "integrators/tableau.hpp"

namespace rb::methods {

// Fehlberg 7(8) as Boost.Odeint's runge_kutta_fehlberg78: 13 stages, no
// FSAL (its first stage is evaluated after acceptance), advances with the
// 8th-order solution; the estimate is the 7th-order one's error, O(h^8). No
// dense output: steps land on the outputs. At fixed steps (rkmk8) its
// 13 stages of order 8: what odeint's runge_kutta_fehlberg78 advances with.
// (DOP853's 8th-order weights at fixed step reach 1e-13 on valley-sideways
// by h = 1/16, still converging from above, too soon for the registry's
// order test to see order 8.)
inline Tableau fehlberg78() {
  TableauCoefficients p;
  p.name = "f78";
  p.order = 8;
  // clang-format off
  p.a = matrix(13, {
    {1, 0, 2.0 / 27},
    {2, 0, 1.0 / 36}, {2, 1, 1.0 / 12},
    {3, 0, 1.0 / 24}, {3, 2, 1.0 / 8},
    {4, 0, 5.0 / 12}, {4, 2, -25.0 / 16}, {4, 3, 25.0 / 16},
    {5, 0, 1.0 / 20}, {5, 3, 1.0 / 4}, {5, 4, 1.0 / 5},
    {6, 0, -25.0 / 108}, {6, 3, 125.0 / 108}, {6, 4, -65.0 / 27}, {6, 5, 125.0 / 54},
    {7, 0, 31.0 / 300}, {7, 4, 61.0 / 225}, {7, 5, -2.0 / 9}, {7, 6, 13.0 / 900},
    {8, 0, 2.0}, {8, 3, -53.0 / 6}, {8, 4, 704.0 / 45}, {8, 5, -107.0 / 9}, {8, 6, 67.0 / 90}, {8, 7, 3.0},
    {9, 0, -91.0 / 108}, {9, 3, 23.0 / 108}, {9, 4, -976.0 / 135}, {9, 5, 311.0 / 54}, {9, 6, -19.0 / 60},
    {9, 7, 17.0 / 6}, {9, 8, -1.0 / 12},
    {10, 0, 2383.0 / 4100}, {10, 3, -341.0 / 164}, {10, 4, 4496.0 / 1025}, {10, 5, -301.0 / 82},
    {10, 6, 2133.0 / 4100}, {10, 7, 45.0 / 82}, {10, 8, 45.0 / 164}, {10, 9, 18.0 / 41},
    {11, 0, 3.0 / 205}, {11, 5, -6.0 / 41}, {11, 6, -3.0 / 205}, {11, 7, -3.0 / 41}, {11, 8, 3.0 / 41},
    {11, 9, 6.0 / 41},
    {12, 0, -1777.0 / 4100}, {12, 3, -341.0 / 164}, {12, 4, 4496.0 / 1025}, {12, 5, -289.0 / 82},
    {12, 6, 2193.0 / 4100}, {12, 7, 51.0 / 82}, {12, 8, 33.0 / 164}, {12, 9, 12.0 / 41}, {12, 11, 1.0}});
  p.c = {0, 2.0 / 27, 1.0 / 9, 1.0 / 6, 5.0 / 12, 0.5, 5.0 / 6, 1.0 / 6, 2.0 / 3, 1.0 / 3, 1, 0, 1};
  p.b = {0, 0, 0, 0, 0, 34.0 / 105, 9.0 / 35, 9.0 / 35, 9.0 / 280, 9.0 / 280, 0, 41.0 / 840, 41.0 / 840};
  // clang-format on
  const double q = 41.0 / 840;
  p.e = {-q, 0, 0, 0, 0, 0, 0, 0, 0, 0, -q, q, q};
  p.embedded_order = 7;
  p.source = "Fehlberg (1968), NASA TR R-287, as in Boost.Odeint's runge_kutta_fehlberg78";
  return Tableau(std::move(p));
}

}  // namespace rb::methods

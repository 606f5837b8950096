#pragma once
// Source: Dormand & Prince, A family of embedded Runge-Kutta formulae, J. Comp. Appl. Math. 6 (1980); dense output:
// Shampine (1986).
#include "integrators/methods/coefficients.hpp"
#include "integrators/tableau.hpp"

// the coefficients keep the layout of their tables
// clang-format off
namespace rb::methods {

// Dormand-Prince 5(4) (DOPRI5): FSAL, its error weights use the FSAL stage
// (6 new stages an attempt); Shampine's 4th-order dense output. At fixed
// steps (rkmk5) its 6 stages of order 5.
inline Tableau dormand_prince54() {
  TableauCoefficients p;
  p.name = "dp54";
  p.order = 5;
  p.a = matrix(7, {{1, 0, 1.0 / 5},
                           {2, 0, 3.0 / 40}, {2, 1, 9.0 / 40},
                           {3, 0, 44.0 / 45}, {3, 1, -56.0 / 15}, {3, 2, 32.0 / 9},
                           {4, 0, 19372.0 / 6561}, {4, 1, -25360.0 / 2187}, {4, 2, 64448.0 / 6561},
                           {4, 3, -212.0 / 729},
                           {5, 0, 9017.0 / 3168}, {5, 1, -355.0 / 33}, {5, 2, 46732.0 / 5247}, {5, 3, 49.0 / 176},
                           {5, 4, -5103.0 / 18656},
                           {6, 0, 35.0 / 384}, {6, 2, 500.0 / 1113}, {6, 3, 125.0 / 192}, {6, 4, -2187.0 / 6784},
                           {6, 5, 11.0 / 84}});
  p.c = {0, 0.2, 0.3, 0.8, 8.0 / 9, 1, 1};
  p.b = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
  p.embedded_order = 4;
  p.e = {-71.0 / 57600, 0, 71.0 / 16695, -71.0 / 1920, 17253.0 / 339200, -22.0 / 525, 1.0 / 40};
  p.dense_order = 4;
  p.dense_degree = 4;
  p.dense = {1, -8048581381.0 / 2820520608, 8663915743.0 / 2820520608, -12715105075.0 / 11282082432,
             0, 0, 0, 0,
             0, 131558114200.0 / 32700410799, -68118460800.0 / 10900136933, 87487479700.0 / 32700410799,
             0, -1754552775.0 / 470086768, 14199869525.0 / 1410260304, -10690763975.0 / 1880347072,
             0, 127303824393.0 / 49829197408, -318862633887.0 / 49829197408, 701980252875.0 / 199316789632,
             0, -282668133.0 / 205662961, 2019193451.0 / 616988883, -1453857185.0 / 822651844,
             0, 40617522.0 / 29380423, -110615467.0 / 29380423, 69997945.0 / 29380423};
  p.source = "Dormand & Prince, J. Comp. Appl. Math. 6 (1980); dense output: Shampine (1986)";
  return Tableau(std::move(p));
}

}  // namespace rb::methods
// clang-format on

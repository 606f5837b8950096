#pragma once
// Source: Z. Jackiewicz, A. Marthinsen and B. Owren, "Construction of
// Runge-Kutta methods of Crouch-Grossman type of high order", Adv. Comput.
// Math. 13 (2000) 405-415, example 2: 9 stages, order 5, coefficients to 16
// digits as Lielab's CG5a gives them (each row sums to its c to 1e-16).
// Why F_1 acts first: methods/cg3.hpp.
#include "integrators/families/exp_product/exp_product_scheme.hpp"

// the coefficients keep the layout of their tables
// clang-format off
namespace rb::methods {

// order 5, 9 stages
inline ExpProductScheme cg5a() {
  return crouch_grossman("cg5a", 5,
                         {{0.5119828014137712},
                          {0.1256672120643583, 0.7516202380829815},
                          {-0.1859318985660963, 0.9805295406563367, -0.5333302514616872},
                          {0.1693767277911736, 0.9505578305836004, -0.2601241719456298, -0.2298819100175240},
                          {-0.3672779810475256, -0.0086029950554851, -0.0010336337263253, 0.4747844514543335,
                           -0.1827675787966842},
                          {-0.1967584902954152, -0.0841805485664162, -0.0269530236366960, 0.7559747536983863,
                           -0.0238706198984107, 0.0482925299135956},
                          {-0.5309452158934434, 0.0197456651284920, -0.0890782597312347, 1.1112114193183167,
                           -0.2549231869664070, 0.0690881269948897, -0.0190658555145840},
                          {0.0, -0.1116041993954347, 0.0007837329078394, 0.1273989332794543, -0.2951798037735399,
                           -0.5806798044068681, -0.3715982236980106, 1.1170906343009428}},
                         {0.7927513978455029, 0.0, 0.3490698579749237, 0.3139686995007973, -0.4266876632081064,
                          -0.8094238190622946, 1.3450516465346317, -0.9242094915998407, 0.3594793720143862},
                         "Jackiewicz, Marthinsen and Owren (2000), example 2");
}

}  // namespace rb::methods
// clang-format on

#pragma once
// Source: Z. Jackiewicz, A. Marthinsen and B. Owren, "Construction of
// Runge-Kutta methods of Crouch-Grossman type of high order", Adv. Comput.
// Math. 13 (2000) 405-415 (the "Appl. Numer. Math. 34"), example 1,
// 5 stages, order 4. As in ManifoldDiffEq.jl's CG4a and DiffMan; some
// copies print a54 = -1.1092979392113565, but only -1.1092979392113465 sums
// row 5 to c_5 = 0.8768903263420429. Why F_1 acts first: methods/cg3.hpp.
#include "integrators/families/exp_product/exp_product_scheme.hpp"

// the coefficients keep the layout of their tables
// clang-format off
namespace rb::methods {

// order 4, 5 stages
inline ExpProductScheme cg4a() {
  return crouch_grossman("cg4a", 4,
                         {{0.8177227988124852},
                          {0.3199876375476427, 0.0659864263556022},
                          {0.9214417194464946, 0.4997857776773573, -1.0969984448371582},
                          {0.3552358559023322, 0.2390958372307326, 1.3918565724203246, -1.1092979392113465}},
                         {0.1370831520630755, -0.0183698531564020, 0.7397813985370780, -0.1907142565505889,
                          0.3322195591068374},
                         "Jackiewicz, Marthinsen and Owren (2000), example 1");
}

}  // namespace rb::methods
// clang-format on

#pragma once
// Source: E. Celledoni, A. Marthinsen and B. Owren, "Commutator-free Lie
// group methods", Future Generation Computer Systems 19 (2003) 341-352, the
// order-3 method on Heun's third-order tableau (c = (0, 1/3, 2/3), b = (1/4,
// 0, 3/4)):
//   Y_2 = exp(F_1 / 3) y_0,  Y_3 = exp(2 F_2 / 3) y_0,
//   y_1 = exp(-F_1 / 12 + 3 F_3 / 4) exp(F_1 / 3) y_0,
// the rightmost factor acting first. For omega(t) = omega_0 + t omega_1 the
// update's commutator term (1/2)[X_2, X_1] is h^3 [omega_1, omega_0] / 12,
// the Magnus series' term, as cf4's (methods/cf4.hpp).
#include "integrators/families/exp_product/exp_product_scheme.hpp"

// the coefficients keep the layout of their tables
// clang-format off
namespace rb::methods {

// order 3, 3 stages, 2 exponentials in the update
inline ExpProductScheme cf3() {
  ExpProductScheme s;
  s.name = "cf3";
  s.family = "cf";
  s.kind = "commutator-free";
  s.order = 3;
  s.stages = {
      {},
      {{1.0 / 3}},
      {{0.0, 2.0 / 3}},
  };
  s.update = {{1.0 / 3}, {-1.0 / 12, 0.0, 3.0 / 4}};
  s.source = "Celledoni, Marthinsen and Owren, FGCS 19 (2003), the order-3 method";
  return s;
}

}  // namespace rb::methods
// clang-format on

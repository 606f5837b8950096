#pragma once
// Source: E. Celledoni, A. Marthinsen and B. Owren, "Commutator-free Lie
// group methods", Future Generation Computer Systems 19 (2003) 341-352, the
// order-4 method with c = (0, 1/2, 1/2, 1):
//   Y_2 = exp(F_1 / 2) y_0,  Y_3 = exp(F_2 / 2) y_0,
//   Y_4 = exp(F_3 - F_1 / 2) Y_2,
//   y_1 = exp((-F_1 + 2 F_2 + 2 F_3 + 3 F_4) / 12) exp((3 F_1 + 2 F_2 + 2 F_3 - F_4) / 12) y_0,
// products read right to left (the rightmost factor acts first). OpenMC's
// CF4 depletion integrator has the same stages. Checked in test_cf_cg.cpp:
// the z part sums to RK4's tableau, and for R' = hat(omega(t)) R the
// update's commutator term (1/2)[X_2, X_1] with X_1, X_2 its two exponents
// is h^3 [omega_1, omega_0] / 12 for omega(t) = omega_0 + t omega_1, the
// Magnus series' term; composed the other way it has the opposite sign.
#include "integrators/families/exp_product/exp_product_scheme.hpp"

// the coefficients keep the layout of their tables
// clang-format off
namespace rb::methods {

// order 4, 4 stages
inline ExpProductScheme cf4() {
  ExpProductScheme s;
  s.name = "cf4";
  s.family = "cf";
  s.kind = "commutator-free";
  s.order = 4;
  s.stages = {
      {},
      {{0.5}},
      {{0.0, 0.5}},
      {{0.5}, {-0.5, 0.0, 1.0}},  // Y_2's factor, then exp(F_3 - F_1 / 2)
  };
  s.update = {{3.0 / 12, 2.0 / 12, 2.0 / 12, -1.0 / 12}, {-1.0 / 12, 2.0 / 12, 2.0 / 12, 3.0 / 12}};
  s.source = "Celledoni, Marthinsen and Owren, FGCS 19 (2003)";
  return s;
}

// order 4 with an embedded order-3 update (cf4-adaptive). The embedded
// update needs a fifth stage, F_5 = F(y_1) at the new state (c_5 = 1, its
// orientation cf4's update): on the classical side b^ = (1/6, 1/3, 1/3,
// 1/6 - g, g) with stage 5's row = b meets every order-3 condition for any g
// and misses order 4's sum b^ A c^2 = 1/12 by g/12, so the estimate is
// O(h^4); split as exp(h beta.F) exp(h alpha.F) with alpha cf4's first
// exponent, its commutator term h^3 (sum beta c sum alpha - sum beta sum
// alpha c) [omega_1, omega_0] / 2 = h^3 [omega_1, omega_0] / 12 is the Magnus
// term, the one Lie condition of order 3. g = 1/6 (b^_4 = 0). Derived here
// in the way of Celledoni, Marthinsen and Owren's methods; checked in
// test_cf_cg_adaptive.cpp (the embedded update read as a method of its own:
// order 3 where R feeds back).
inline ExpProductScheme cf4_pair() {
  ExpProductScheme s = cf4();
  const double g = 1.0 / 6;
  s.stages.push_back(s.update);  // F_5 at y_1
  s.embedded = {{3.0 / 12, 2.0 / 12, 2.0 / 12, -1.0 / 12, 0.0}, {-1.0 / 12, 2.0 / 12, 2.0 / 12, 3.0 / 12 - g, g}};
  s.embedded_order = 3;
  s.source += "; embedded order-3 update on an extra stage at y_1 (rollbench, docs/integrators.md)";
  return s;
}

}  // namespace rb::methods
// clang-format on

#pragma once
// Source: B. Owren and A. Marthinsen, "Runge-Kutta methods adapted to
// manifolds and based on rigid frames", BIT 39 (1999) 116-142, the order-3
// Crouch-Grossman method (first given by Crouch and Grossman, J. Nonlinear
// Sci. 3 (1993)): a21 = 3/4, a31 = 119/216, a32 = 17/108,
// b = (13/51, -2/3, 24/17). As in ManifoldDiffEq.jl's CG3 and DiffMan.
//
// cg3_pair: cg3 with the embedded weights b^ = (3/4, 31/4, -15/2) on the
// same stages, from K. Engo and A. Marthinsen, "Modeling and solution of
// some mechanical problems on Lie groups", Multibody System Dynamics 2
// (1998) 71-88, tableau (5); ManifoldDiffEq.jl's CG2_3 uses them (it
// propagates b^; here cg3's b propagates and b^ only measures the error).
// b^ meets the classical order-2 conditions (sum b^ = 1, sum b^ c = 1/2;
// order 2 needs no other Crouch-Grossman condition) and misses order 3
// (sum b^ c^2 = 229/384, not 1/3), so the estimate is O(h^3); both are
// checked in test_cf_cg_adaptive.cpp.
//
// Why F_1 acts first (every Crouch-Grossman scheme): the order conditions
// are derived for y_1 = exp(h b_s F_s) o ... o exp(h b_1 F_1) (y_0), each
// flow applied to the result of the one before, so F_1's flow acts first
// and F_s's last (likewise in the stages). Already for R' = hat(omega(t)) R
// the order-3 condition fixes the sign: the product's h^3 commutator term is
// (h^3 / 2) sum_{i>j} b_i b_j (c_i - c_j) [omega_1, omega_0] and the Magnus
// series' is h^3 [omega_1, omega_0] / 12, so sum_{i>j} b_i b_j (c_i - c_j)
// = 1/6, which cg3 and cg4a satisfy; composed the other way the sum enters
// with the opposite sign, so the reversed methods are order 2 in R.
#include "integrators/families/exp_product/exp_product_scheme.hpp"

namespace rb::methods {

// order 3, 3 stages
inline ExpProductScheme cg3() {
  return crouch_grossman("cg3", 3, {{3.0 / 4}, {119.0 / 216, 17.0 / 108}}, {13.0 / 51, -2.0 / 3, 24.0 / 17},
                         "Owren and Marthinsen, BIT 39 (1999)");
}

// order 3 with an embedded order-2 update
inline ExpProductScheme cg3_pair() {
  ExpProductScheme s = cg3();
  s.embedded = one_field_each({3.0 / 4, 31.0 / 4, -15.0 / 2});
  s.embedded_order = 2;
  s.source += "; embedded order-2 weights: Engo and Marthinsen (1998), tableau (5)";
  return s;
}

}  // namespace rb::methods

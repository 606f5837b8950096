// The coefficients, and why F_1 acts first.
//
// cg3: B. Owren and A. Marthinsen, "Runge-Kutta methods adapted to manifolds
// and based on rigid frames", BIT 39 (1999) 116-142, the order-3 method
// (first given by Crouch and Grossman, J. Nonlinear Sci. 3 (1993)):
// a21 = 3/4, a31 = 119/216, a32 = 17/108, b = (13/51, -2/3, 24/17). As in
// ManifoldDiffEq.jl's CG3 and DiffMan.
//
// cg4a: Z. Jackiewicz, A. Marthinsen and B. Owren, "Construction of
// Runge-Kutta methods of Crouch-Grossman type of high order", Adv. Comput.
// Math. 13 (2000) 405-415 (the "Appl. Numer. Math. 34"), example 1,
// 5 stages, order 4. As in ManifoldDiffEq.jl's CG4a and DiffMan; some
// copies print a54 = -1.1092979392113565, but only -1.1092979392113465 sums
// row 5 to c_5 = 0.8768903263420429.
//
// cg3-adaptive: cg3 with the embedded weights b^ = (3/4, 31/4, -15/2) on
// the same stages, from K. Engo and A. Marthinsen, "Modeling and solution
// of some mechanical problems on Lie groups", Multibody System Dynamics 2
// (1998) 71-88, tableau (5); ManifoldDiffEq.jl's CG2_3 uses them (it
// propagates b^; here cg3's b propagates and b^ only measures the error).
// b^ meets the classical order-2 conditions (sum b^ = 1, sum b^ c = 1/2;
// order 2 needs no other Crouch-Grossman condition) and misses order 3
// (sum b^ c^2 = 229/384, not 1/3), so the estimate is O(h^3); both are
// checked in test_cf_cg_adaptive.cpp.
//
// The ordering: the Crouch-Grossman order conditions are derived for
// y_1 = exp(h b_s F_s) o ... o exp(h b_1 F_1) (y_0), each flow applied to
// the result of the one before, so F_1's flow acts first and F_s's last
// (likewise in the stages). Already for R' = hat(omega(t)) R the order-3
// condition fixes the sign: the product's h^3 commutator term is
// (h^3 / 2) sum_{i>j} b_i b_j (c_i - c_j) [omega_1, omega_0] and the Magnus
// series' is h^3 [omega_1, omega_0] / 12, so sum_{i>j} b_i b_j (c_i - c_j)
// = 1/6, which both methods satisfy; composed the other way the sum enters
// with the opposite sign, so the reversed methods are order 2 in R.
#include "integrators/steppers/crouch_grossman.hpp"

namespace rb::schemes {

namespace {

// exp(w_s F_s) ... exp(w_1 F_1): one field per exponential, F_1 first
ExpProduct one_field_each(const std::vector<double>& w) {
  ExpProduct p;
  for (std::size_t j = 0; j < w.size(); ++j) {
    FieldSum f(j + 1, 0.0);
    f[j] = w[j];
    p.push_back(f);
  }
  return p;
}

// the Crouch-Grossman shape
ExpProductScheme crouch_grossman(std::string name, int order, const std::vector<std::vector<double>>& a,
                                 const std::vector<double>& b, std::string source) {
  ExpProductScheme s;
  s.name = std::move(name);
  s.family = "cg";
  s.kind = "Crouch-Grossman";
  s.order = order;
  s.stages.push_back({});
  for (const auto& row : a) s.stages.push_back(one_field_each(row));
  s.update = one_field_each(b);
  s.source = std::move(source);
  return s;
}

}  // namespace

ExpProductScheme cg3() {
  return crouch_grossman("cg3", 3, {{3.0 / 4}, {119.0 / 216, 17.0 / 108}}, {13.0 / 51, -2.0 / 3, 24.0 / 17},
                         "Owren and Marthinsen, BIT 39 (1999)");
}

ExpProductScheme cg3_pair() {
  ExpProductScheme s = cg3();
  s.name = "cg3-adaptive";
  s.embedded = one_field_each({3.0 / 4, 31.0 / 4, -15.0 / 2});
  s.embedded_order = 2;
  s.source += "; embedded order-2 weights: Engo and Marthinsen (1998), tableau (5)";
  return s;
}

ExpProductScheme cg4a() {
  return crouch_grossman("cg4a", 4,
                         {{0.8177227988124852},
                          {0.3199876375476427, 0.0659864263556022},
                          {0.9214417194464946, 0.4997857776773573, -1.0969984448371582},
                          {0.3552358559023322, 0.2390958372307326, 1.3918565724203246, -1.1092979392113465}},
                         {0.1370831520630755, -0.0183698531564020, 0.7397813985370780, -0.1907142565505889,
                          0.3322195591068374},
                         "Jackiewicz, Marthinsen and Owren (2000), example 1");
}

}  // namespace rb::schemes

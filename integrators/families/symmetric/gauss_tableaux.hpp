#pragma once
// The implicit Gauss-Legendre collocation methods of 1, 2 and 3 stages
// (orders 2, 4, 6; symmetric), and the symmetric compositions that raise a
// symmetric order-2 method to orders 4 and 6 (docs/model.md, "Symmetric
// implicit methods"). Tests check the collocation conditions and the
// composition's order conditions numerically (SymmetricMethods.*).
#include <cmath>
#include <string>
#include <vector>

namespace rb::methods {

// An implicit Runge-Kutta tableau: s stages, a (s x s, row-major), b, c.
struct ImplicitTableau {
  std::string name;
  int order = 0;
  int stages = 0;
  std::vector<double> a, b, c;
  std::string source;
};

// Source: Butcher (1964), "Implicit Runge-Kutta processes"; Hairer, Lubich &
// Wanner, Geometric Numerical Integration, II.1.3, Table 1.1 (s = 2, 3).
// The nodes are the zeros of the shifted Legendre polynomial of degree s.
inline ImplicitTableau gauss(int stages) {
  const std::string source = "Gauss-Legendre collocation, Butcher (1964); Hairer, Lubich & Wanner, GNI II.1.3";
  if (stages == 1) return {"gauss2", 2, 1, {0.5}, {1.0}, {0.5}, source};  // the implicit midpoint rule
  if (stages == 2) {
    const double r = std::sqrt(3.0) / 6;
    return {"gauss4", 4, 2, {0.25, 0.25 - r, 0.25 + r, 0.25}, {0.5, 0.5}, {0.5 - r, 0.5 + r}, source};
  }
  const double q = std::sqrt(15.0);
  return {"gauss6",
          6,
          3,
          {5.0 / 36, 2.0 / 9 - q / 15, 5.0 / 36 - q / 30,  //
           5.0 / 36 + q / 24, 2.0 / 9, 5.0 / 36 - q / 24,  //
           5.0 / 36 + q / 30, 2.0 / 9 + q / 15, 5.0 / 36},
          {5.0 / 18, 4.0 / 9, 5.0 / 18},
          {0.5 - q / 10, 0.5, 0.5 + q / 10},
          source};
}

// The substeps gamma_k h of the symmetric composition of a symmetric method
// of order 2 that has the given order (2: the method itself).
// Source: Yoshida (1990), Phys. Lett. A 150; Suzuki (1990); Hairer, Lubich &
// Wanner, GNI II.4 (the "triple jump"): a symmetric method Phi of even order
// p composed as Phi_{g1 h} Phi_{g2 h} Phi_{g1 h} with 2 g1 + g2 = 1 and
// 2 g1^(p+1) + g2^(p+1) = 0, g1 = 1 / (2 - 2^(1/(p+1))), is symmetric and
// of order p + 2. Order 4: one triple jump (3 substeps); order 6: the triple
// jump of order 6 applied to the order-4 one (9 substeps).
inline std::vector<double> triple_jump(int order) {
  std::vector<double> gammas{1.0};
  for (int p = 2; p < order; p += 2) {
    const double g1 = 1.0 / (2.0 - std::pow(2.0, 1.0 / (p + 1))), g2 = 1.0 - 2.0 * g1;
    std::vector<double> next;
    for (const double g : {g1, g2, g1})
      for (const double inner : gammas) next.push_back(g * inner);
    gammas = next;
  }
  return gammas;
}

}  // namespace rb::methods

#pragma once
// The embedded pair type of the high-order methods (one file each in this
// folder): coefficients, orders, error weights, dense-output weights.
// Tableau checks order conditions up to 4 only;
// tests/integrators/test_lie_adaptive.cpp checks every rooted tree up to
// each method's order, and the dense outputs' continuous orders.
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "integrators/tableau.hpp"

namespace rb {

// An embedded explicit Runge-Kutta pair with a dense output. Stage i has node
// c[i] and row a[i][*] (row-major, total x total). Three groups of stages:
//   0 .. stages-1        evaluated in every attempt; b and e weight only these
//   fsal                 the stage at (t + h, y_new): its row of A equals b and
//                        c = 1, so its right-hand side starts the next step;
//                        fsal < stages when the error estimate uses it (BS32,
//                        DP54), fsal == stages when it is evaluated only after
//                        an accepted step (DP853; and F78, which has no FSAL
//                        stage but needs f(y_new) next all the same)
//   up to total-1        the extra stages only the dense output needs
struct EmbeddedPair {
  std::string name;
  int order = 0;        // of b, the solution that is propagated
  int error_order = 0;  // the local error estimate is O(h^error_order)
  int stages = 0;
  int fsal = 0;
  int total = 0;
  std::vector<double> a, c;
  std::vector<double> b;   // total entries, zero past the propagating stages
  std::vector<double> e;   // b - b_hat: h sum e_i k_i estimates the local error
  std::vector<double> e3;  // DP853's 3rd-order estimate b - b_hat3 (Hairer's "stretched" error); empty elsewhere
  int dense_order = 0;     // of the continuous extension; 0: none
  int dense_degree = 0;
  // b_i(theta) = sum_k dense[i * dense_degree + k] theta^(k + 1): the weights
  // of the step to t + theta h; b_i(1) = b_i.
  std::vector<double> dense;

  double a_at(int i, int j) const { return a[static_cast<std::size_t>(i * total + j)]; }
  // The propagating method alone as a fixed-step tableau: the stages up to
  // the last non-zero b.
  Tableau tableau(const std::string& tableau_name) const {
    int s = total;
    while (s > 0 && b[static_cast<std::size_t>(s - 1)] == 0.0) --s;
    std::vector<double> as(static_cast<std::size_t>(s * s));
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) as[static_cast<std::size_t>(i * s + j)] = a_at(i, j);
    return Tableau(tableau_name, order, as, {b.begin(), b.begin() + s}, {c.begin(), c.begin() + s});
  }
};

namespace pairs::detail {

struct Entry {
  int i, j;
  double value;
};

inline std::vector<double> matrix(int n, std::initializer_list<Entry> entries) {
  std::vector<double> m(static_cast<std::size_t>(n * n), 0.0);
  for (const Entry& x : entries) m[static_cast<std::size_t>(x.i * n + x.j)] = x.value;
  return m;
}
}  // namespace pairs::detail

}  // namespace rb

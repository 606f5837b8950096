#pragma once
// An explicit Runge-Kutta method as data, one type for every method: the
// coefficients (A, b, c) and the declared order, and where the method has
// them its embedded error weights, a second ("stretched") estimate, a dense
// output and its source. It checks itself on construction: strictly
// lower-triangular A, c_i = sum_j a_ij, and the order conditions of every
// rooted tree (integrators/order_conditions.hpp) for b up to the declared
// order and for each embedded member up to its order.
//
// Stages come in up to three groups, all derived from the coefficients:
//   0 .. stages()-1          weighted by b: what a fixed step evaluates;
//   .. attempt_stages()-1    also weighted by an error estimate: what an
//                            adaptive attempt evaluates (DP54's and BS32's
//                            error weights use their FSAL stage);
//   .. total_stages()-1      only the dense output needs these (DP853).
// The FSAL stage (fsal_stage()) is the one whose row of A equals b and whose
// c is 1: its right-hand side is f(t + h, y_new), the next step's first.
#include <optional>
#include <string>
#include <vector>

#include "integrators/order_conditions.hpp"

namespace rb {

// What a method file gives (integrators/methods/). Sizes: s stages, a is
// s x s row-major, b, c, e and e_stretched s entries, dense s x dense_degree.
struct TableauCoefficients {
  std::string name;
  int order = 0;  // of b, the solution that is propagated
  std::vector<double> a, b, c;
  // e = b - b_hat (or b_hat - b, as DOPRI5's and BS32's sources give it):
  // h sum e_i k_i estimates the local error; b_hat has order
  // embedded_order. Empty: no error estimate.
  std::vector<double> e;
  int embedded_order = 0;
  // A second, lower-order estimate b - b_hat2 (order stretched_order),
  // combined with e as DOP853 does (Hairer's "stretched" error
  // |err|^2 / sqrt(|err|^2 + 0.01 |err2|^2)). Empty elsewhere.
  std::vector<double> e_stretched;
  int stretched_order = 0;
  // The continuous extension of order dense_order: the weights of the step
  // to t + theta h are b_i(theta) = sum_k dense[i * dense_degree + k]
  // theta^(k + 1), with b_i(1) = b_i. Empty: no dense output.
  std::vector<double> dense;
  int dense_order = 0;
  int dense_degree = 0;
  std::string source;  // the citation
  // How close each order condition, row sum (c_i = sum_j a_ij) and dense
  // end (b_i(1) = b_i) must hold. The shipped tableaus are exact to
  // rounding; a tableau file may loosen it for a table printed to ~10 digits.
  double order_tolerance = kOrderConditionTolerance;
};

class Tableau {
 public:
  // Throws InputError naming the key ("a", "b", "c", "order", "e", ...) of
  // what fails.
  explicit Tableau(TableauCoefficients coefficients);
  // A plain tableau (no error estimate, no dense output).
  Tableau(std::string name, int order, std::vector<double> a, std::vector<double> b, std::vector<double> c,
          std::string source = {});

  const std::string& name() const { return k_.name; }
  int order() const { return k_.order; }
  const std::string& source() const { return k_.source; }
  // All of it, as given (to build a variant of a shipped tableau).
  const TableauCoefficients& coefficients() const { return k_; }

  // The stages b weights (up to its last non-zero weight).
  int stages() const { return stages_; }
  // The stages an adaptive attempt evaluates: those b or an error estimate weights.
  int attempt_stages() const { return attempt_stages_; }
  // Every stage, dense-output stages included.
  int total_stages() const { return static_cast<int>(k_.b.size()); }
  // The FSAL stage (row of A = b exactly, c = 1), if there is one.
  std::optional<int> fsal_stage() const { return fsal_; }
  // Whether an adaptive attempt evaluates the FSAL stage (its error weights
  // use it: BS32, DP54); otherwise f(y_new) is one more evaluation per step.
  bool fsal_in_attempt() const { return fsal_ && *fsal_ < attempt_stages_; }

  // i, j < total_stages(); b(i) = 0 for i >= stages().
  double a(int i, int j) const { return k_.a[static_cast<std::size_t>(i * total_stages() + j)]; }
  double b(int i) const { return k_.b[static_cast<std::size_t>(i)]; }
  double c(int i) const { return k_.c[static_cast<std::size_t>(i)]; }
  const std::vector<double>& a_row_major() const { return k_.a; }
  const std::vector<double>& b_weights() const { return k_.b; }  // total_stages() entries

  // The error estimate, where there is one.
  bool has_error_estimate() const { return !k_.e.empty(); }
  const std::vector<double>& e() const { return k_.e; }
  int embedded_order() const { return k_.embedded_order; }
  const std::vector<double>& e_stretched() const { return k_.e_stretched; }
  int stretched_order() const { return k_.stretched_order; }
  // k with error norm = O(h^k): min(order, embedded order) + 1, and with a
  // stretched estimate 2 k - k2 (DOP853: 2 * 6 - 4 = 8).
  int error_order() const;

  // The dense output, where there is one (dense_order() > 0).
  int dense_order() const { return k_.dense_order; }
  int dense_degree() const { return k_.dense_degree; }
  const std::vector<double>& dense() const { return k_.dense; }

  // The largest p <= 10 (kMaxConditionOrder) whose order conditions hold to
  // order_tolerance (1e-12 unless the coefficients say otherwise).
  int satisfied_order() const;

 private:
  TableauCoefficients k_;
  int stages_ = 0, attempt_stages_ = 0;
  std::optional<int> fsal_;
};

// The most stages any tableau may have; step loops keep this many stage
// vectors on the stack. Past the 17 of Feagin's 10(8) and the 25 of his
// 12(10), whose order conditions are checked to order 10.
inline constexpr int kMaxStages = 32;

}  // namespace rb

#pragma once
// Butcher's order conditions of an explicit Runge-Kutta method, one per
// rooted tree: a method has order p when sum_i b_i Phi_i(t) = 1 / gamma(t)
// for every rooted tree t with at most p vertices (Hairer, Norsett & Wanner,
// Solving ODEs I, II.2). The checker works on plain data (stages, A
// row-major, b, c) so that any tableau type, a tableau file or a test can
// call it.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rb {

// Rooted trees are enumerated up to this order (1205 trees; 200 up to 8).
inline constexpr int kMaxConditionOrder = 10;

// An order condition holds when |Phi(t) - 1/gamma(t)| is at most this
// (unless a tableau file sets its own order_tolerance).
inline constexpr double kOrderConditionTolerance = 1e-12;
// The loosest tolerance a tableau may ask for. A looser one certifies broken
// methods: an RK4 with b_1, b_2 moved by 1.8e-6 is truly order 1 (its error
// stops falling at ~1e-8), yet meets every order-4 condition to 1e-6.
inline constexpr double kMaxOrderTolerance = 1e-10;
// "a number > 0 and at most 1e-10 (...)": what an order_tolerance must be.
std::string order_tolerance_rule();

struct RootedTree {
  int order = 1;              // |t|, the number of vertices
  std::vector<int> children;  // the root's subtrees as indices into rooted_trees(), non-decreasing
  double density = 1.0;       // gamma(t) = |t| times the children's densities
  std::string name;           // bracket notation: tau, [tau], [tau^2], [tau[tau]], ... (Unicode)
};

// Every rooted tree of order 1 to kMaxConditionOrder, each once, in order of
// increasing order (1, 1, 2, 4, 9, 20, 48, 115, 286, 719 trees).
const std::vector<RootedTree>& rooted_trees();

// The first tree whose condition fails.
struct OrderConditionFailure {
  int order = 0;          // of the tree
  std::string tree;       // its name, as RootedTree::name
  double weight = 0.0;    // Phi(t) = sum_i w_i Phi_i(t)
  double expected = 0.0;  // theta^|t| / gamma(t)
  double residual = 0.0;  // weight - expected
};

struct OrderConditionCheck {
  // the highest p <= max_order whose conditions (all trees of order <= p) hold
  int satisfied_order = 0;
  // the first failing tree of order satisfied_order + 1; none when
  // satisfied_order == max_order
  std::optional<OrderConditionFailure> failure;
};

// Checks the weights w of an explicit method with nodes c and matrix a (s x s,
// row-major, a_ij = a[i * s + j]) against every tree up to max_order
// (1 .. kMaxConditionOrder). The stage weights Phi_i use c for the subtree
// tau (sum_j a_ij = c_i, which a tableau checks beforehand). theta != 1
// checks a continuous extension's weights b_i(theta) against
// theta^|t| / gamma(t) instead (dense output). A condition holds when its
// residual is at most tolerance. Throws std::invalid_argument when the sizes
// do not fit.
OrderConditionCheck check_order_conditions(int stages, std::span<const double> a, std::span<const double> w,
                                           std::span<const double> c, int max_order, double theta = 1.0,
                                           double tolerance = kOrderConditionTolerance);

// An exact coefficient p/q (q > 0), as a tableau file may give it ("1/6").
struct Fraction {
  std::int64_t numerator = 0;
  std::int64_t denominator = 1;
};

// The same check in exact rational arithmetic (theta = 1): a condition holds
// only when sum_i w_i Phi_i(t) equals 1/gamma(t) exactly. The failure's
// numbers are the exact values rounded to doubles.
OrderConditionCheck check_order_conditions_exact(int stages, std::span<const Fraction> a, std::span<const Fraction> w,
                                                 std::span<const Fraction> c, int max_order);

// "tree [tau^2] of order 3: Phi = 0.3, 1/gamma = 0.333333333333333, residual
// -3.333e-02": Phi and 1/gamma to 15 digits, so that any residual above the
// default tolerance shows in them
// (theta^|t|/gamma for a continuous extension).
std::string describe(const OrderConditionFailure& failure);

}  // namespace rb

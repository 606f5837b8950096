#include "integrators/order_conditions.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

namespace rb {

namespace {

// "²" .. "⁹": a repeated subtree in a name, as Butcher writes [τ²]
std::string superscript(int n) {
  static const char* const digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string s;
  for (const char ch : std::to_string(n)) s += digits[ch - '0'];
  return s;
}

// [child child ...], identical children (adjacent, the list is sorted) as powers
std::string bracket_name(const std::vector<RootedTree>& trees, const std::vector<int>& children) {
  if (children.empty()) return "τ";
  std::string name = "[";
  for (std::size_t k = 0; k < children.size();) {
    std::size_t run = k;
    while (run < children.size() && children[run] == children[k]) ++run;
    name += trees[static_cast<std::size_t>(children[k])].name;
    if (run - k > 1) name += superscript(static_cast<int>(run - k));
    k = run;
  }
  return name + "]";
}

// A tree of order n is a root whose subtrees form a multiset of smaller
// trees with orders summing to n - 1: choosing them in non-decreasing index
// order makes each multiset, hence each tree, appear exactly once.
std::vector<RootedTree> enumerate_trees(int max_order) {
  std::vector<RootedTree> trees = {{1, {}, 1.0, "τ"}};
  for (int n = 2; n <= max_order; ++n) {
    const std::size_t smaller = trees.size();
    std::vector<int> picked;
    std::function<void(int, std::size_t)> pick = [&](int left, std::size_t from) {
      if (left == 0) {
        double density = n;
        for (int child : picked) density *= trees[static_cast<std::size_t>(child)].density;
        RootedTree tree{n, picked, density, bracket_name(trees, picked)};
        trees.push_back(std::move(tree));
        return;
      }
      for (std::size_t i = from; i < smaller; ++i)
        if (trees[i].order <= left) {
          picked.push_back(static_cast<int>(i));
          pick(left - trees[i].order, i);
          picked.pop_back();
        }
    };
    pick(n - 1, 0);
  }
  return trees;
}

}  // namespace

const std::vector<RootedTree>& rooted_trees() {
  static const std::vector<RootedTree> trees = enumerate_trees(kMaxConditionOrder);
  return trees;
}

namespace {

void check_sizes(int stages, std::size_t a, std::size_t w, std::size_t c, int max_order) {
  const auto s = static_cast<std::size_t>(stages);
  if (stages < 1 || a != s * s || w != s || c != s)
    throw std::invalid_argument("check_order_conditions: a must be s x s, w and c of size s");
  if (max_order < 1 || max_order > kMaxConditionOrder)
    throw std::invalid_argument("check_order_conditions: max_order must be 1 to " + std::to_string(kMaxConditionOrder));
}

// The tree-by-tree check for any number type; expected(tree) is the value
// its condition asks for, holds(weight, expected) decides it.
template <class Number, class Expected, class Holds>
OrderConditionCheck check_trees(std::size_t s, std::span<const Number> a, std::span<const Number> w,
                                std::span<const Number> c, int max_order, Expected expected_of, Holds holds) {
  const std::vector<RootedTree>& trees = rooted_trees();
  // per tree t: Phi_i(t) at each stage, and (A Phi(t))_i, the factor t
  // contributes to a parent's Phi_i (c_i for t = tau)
  std::vector<std::vector<Number>> a_phi;
  a_phi.reserve(trees.size());
  std::vector<Number> phi(s);
  OrderConditionCheck check;
  for (const RootedTree& tree : trees) {
    if (tree.order > max_order) break;
    for (std::size_t i = 0; i < s; ++i) {
      Number p = 1;
      for (int child : tree.children) p *= a_phi[static_cast<std::size_t>(child)][i];
      phi[i] = p;
    }
    Number weight = 0;
    for (std::size_t i = 0; i < s; ++i) weight += w[i] * phi[i];
    const Number expected = expected_of(tree);
    if (!holds(weight, expected)) {
      check.satisfied_order = tree.order - 1;
      check.failure =
          OrderConditionFailure{tree.order, tree.name, static_cast<double>(weight), static_cast<double>(expected),
                                static_cast<double>(Number(weight - expected))};
      return check;
    }
    std::vector<Number> next(s, Number(0));
    for (std::size_t i = 0; i < s; ++i) {
      if (tree.children.empty()) {
        next[i] = c[i];
        continue;
      }
      for (std::size_t j = 0; j < s; ++j) next[i] += a[i * s + j] * phi[j];
    }
    a_phi.push_back(std::move(next));
  }
  check.satisfied_order = max_order;
  return check;
}

}  // namespace

OrderConditionCheck check_order_conditions(int stages, std::span<const double> a, std::span<const double> w,
                                           std::span<const double> c, int max_order, double theta, double tolerance) {
  check_sizes(stages, a.size(), w.size(), c.size(), max_order);
  return check_trees<double>(
      static_cast<std::size_t>(stages), a, w, c, max_order,
      [theta](const RootedTree& tree) { return std::pow(theta, tree.order) / tree.density; },
      [tolerance](double weight, double expected) { return std::abs(weight - expected) <= tolerance; });
}

OrderConditionCheck check_order_conditions_exact(int stages, std::span<const Fraction> a, std::span<const Fraction> w,
                                                 std::span<const Fraction> c, int max_order) {
  using boost::multiprecision::cpp_rational;
  check_sizes(stages, a.size(), w.size(), c.size(), max_order);
  const auto exact = [](std::span<const Fraction> f) {
    std::vector<cpp_rational> out;
    for (const Fraction& x : f) out.emplace_back(cpp_rational(x.numerator) / x.denominator);
    return out;
  };
  const std::vector<cpp_rational> qa = exact(a), qw = exact(w), qc = exact(c);
  return check_trees<cpp_rational>(
      static_cast<std::size_t>(stages), qa, qw, qc, max_order,
      [](const RootedTree& tree) { return cpp_rational(1) / static_cast<long long>(tree.density); },
      [](const cpp_rational& weight, const cpp_rational& expected) { return weight == expected; });
}

std::string order_tolerance_rule() {
  char bound[32];
  std::snprintf(bound, sizeof bound, "%g", kMaxOrderTolerance);
  return std::string("a number > 0 and at most ") + bound + " (the order conditions are checked to it)";
}

std::string describe(const OrderConditionFailure& failure) {
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, ": Phi = %.15g, 1/gamma = %.15g, residual %.3e", failure.weight,
                failure.expected, failure.residual);
  return "tree " + failure.tree + " of order " + std::to_string(failure.order) + numbers;
}

}  // namespace rb

// Butcher's order conditions: the rooted trees (counts, densities, names)
// and the checker against tableaux of known order, up to DOP853's order 8,
// and against perturbed weights whose first failing tree is known.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/order_conditions.hpp"
#include "integrators/tableau.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

// A tableau's coefficients as the checker takes them.
struct Plain {
  int s;
  std::vector<double> a, b, c;
};

Plain plain(const Tableau& t) {
  Plain p{t.total_stages(), t.a_row_major(), {}, {}};
  for (int i = 0; i < t.total_stages(); ++i) {
    p.b.push_back(t.b(i));
    p.c.push_back(t.c(i));
  }
  return p;
}

OrderConditionCheck check(const Plain& p, int max_order = kMaxConditionOrder) {
  return check_order_conditions(p.s, p.a, p.b, p.c, max_order);
}

const RootedTree& tree_named(const std::string& name) {
  for (const RootedTree& t : rooted_trees())
    if (t.name == name) return t;
  throw std::runtime_error("no tree " + name);
}

TEST(OrderConditions, TreeCountsPerOrderAreTheKnownOnes) {
  std::vector<int> count(kMaxConditionOrder + 1, 0);
  for (const RootedTree& t : rooted_trees()) ++count[static_cast<std::size_t>(t.order)];
  EXPECT_EQ(count, (std::vector<int>{0, 1, 1, 2, 4, 9, 20, 48, 115, 286, 719}));
  int up_to_8 = 0;
  for (int p = 1; p <= 8; ++p) up_to_8 += count[static_cast<std::size_t>(p)];
  EXPECT_EQ(up_to_8, 200);
}

TEST(OrderConditions, TreesHaveBracketNamesAndTheirDensities) {
  // order <= 4 in full, and the tall and bushy trees of order 8
  const std::vector<std::pair<std::string, double>> known = {
      {"τ", 1},      {"[τ]", 2},     {"[τ²]", 3},     {"[[τ]]", 6}, {"[τ³]", 4},
      {"[τ[τ]]", 8}, {"[[τ²]]", 12}, {"[[[τ]]]", 24}, {"[τ⁷]", 8},  {"[[[[[[[τ]]]]]]]", 40320}};
  for (const auto& [name, density] : known) {
    SCOPED_TRACE(name);
    EXPECT_EQ(tree_named(name).density, density);
  }
  // names are unique, and each tree's order is one plus its children's
  std::set<std::string> names;
  for (const RootedTree& t : rooted_trees()) {
    EXPECT_TRUE(names.insert(t.name).second) << t.name;
    int order = 1;
    for (int child : t.children) order += rooted_trees()[static_cast<std::size_t>(child)].order;
    EXPECT_EQ(order, t.order) << t.name;
  }
}

TEST(OrderConditions, ClassicalTableauxHaveTheirOrderAndNoMore) {
  EXPECT_EQ(check(plain(methods::euler())).satisfied_order, 1);
  EXPECT_EQ(check(plain(methods::heun())).satisfied_order, 2);
  EXPECT_EQ(check(plain(methods::kutta3())).satisfied_order, 3);
  EXPECT_EQ(check(plain(methods::rk4())).satisfied_order, 4);
  EXPECT_EQ(check(plain(methods::rk38())).satisfied_order, 4);
  // docs/formats.md's example file: Ralston's third-order method
  const Plain ralston3{3, {0, 0, 0, 0.5, 0, 0, 0, 0.75, 0}, {2.0 / 9, 1.0 / 3, 4.0 / 9}, {0, 0.5, 0.75}};
  EXPECT_EQ(check(ralston3).satisfied_order, 3);
}

TEST(OrderConditions, HighOrderWeightsHoldEveryTreeOfTheirOrder) {
  EXPECT_EQ(check(plain(methods::dormand_prince54())).satisfied_order, 5);
  // DOP853's 8th-order weights: all 200 trees to order 8, and one of order 9 fails
  const OrderConditionCheck d8 = check(plain(methods::dormand_prince853()));
  EXPECT_EQ(d8.satisfied_order, 8);
  ASSERT_TRUE(d8.failure);
  EXPECT_EQ(d8.failure->order, 9);
  // rkmk8's tableau (Fehlberg's 8th-order member of f78)
  EXPECT_EQ(check(plain(methods::fehlberg78())).satisfied_order, 8);
  EXPECT_EQ(methods::fehlberg78().satisfied_order(), 8);
  EXPECT_EQ(methods::dormand_prince54().satisfied_order(), 5);
}

TEST(OrderConditions, APerturbedWeightNamesItsFirstFailingTreeAndResidual) {
  // moving d from b_2 to b_1 of rk4 (c_1 = c_2 = 1/2) keeps the quadrature
  // conditions; [[τ]] is the first to see it: (A c)_1 = 0, (A c)_2 = 1/4
  Plain rk4 = plain(methods::rk4());
  const double d = 1e-3;
  rk4.b[1] += d;
  rk4.b[2] -= d;
  const OrderConditionCheck r = check(rk4);
  EXPECT_EQ(r.satisfied_order, 2);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->order, 3);
  EXPECT_EQ(r.failure->tree, "[[τ]]");
  EXPECT_NEAR(r.failure->residual, -0.25 * d, 1e-15);
  EXPECT_NEAR(r.failure->expected, 1.0 / 6, 1e-15);
  EXPECT_EQ(describe(*r.failure),
            "tree [[τ]] of order 3: Phi = 0.166416666666667, 1/gamma = 0.166666666666667, residual -2.500e-04");
  // below the tolerance it holds
  Plain tiny = plain(methods::rk4());
  tiny.b[1] += 1e-14;
  tiny.b[2] -= 1e-14;
  EXPECT_EQ(check(tiny).satisfied_order, 4);
}

TEST(OrderConditions, MaxOrderCapsTheCheck) {
  const OrderConditionCheck r = check(plain(methods::rk4()), 3);
  EXPECT_EQ(r.satisfied_order, 3);
  EXPECT_FALSE(r.failure);
  EXPECT_THROW(check(plain(methods::rk4()), kMaxConditionOrder + 1), std::invalid_argument);
  EXPECT_THROW(check_order_conditions(2, std::vector<double>(3), std::vector<double>(2), std::vector<double>(2), 2),
               std::invalid_argument);
}

TEST(OrderConditions, TableauRefusesADeclaredOrderItsTreesDoNotHold) {
  try {
    Tableau("x", 3, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "order");
    EXPECT_EQ(e.message(),
              "tableau 'x' declares order 3 but satisfies the order conditions only to order 2 (tree [τ²] of order 3: "
              "Phi = 0.5, 1/gamma = 0.333333333333333, residual 1.667e-01)");
  }
}

}  // namespace
}  // namespace rb

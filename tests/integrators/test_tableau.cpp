#include <gtest/gtest.h>

#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

TEST(Tableau, NamedTableausSatisfyTheirOrder) {
  EXPECT_EQ(methods::euler().satisfied_order(), 1);
  EXPECT_EQ(methods::heun().satisfied_order(), 2);
  EXPECT_EQ(methods::kutta3().satisfied_order(), 3);
  EXPECT_EQ(methods::rk4().satisfied_order(), 4);
  EXPECT_EQ(methods::rk38().satisfied_order(), 4);
}

std::string error_of(auto&& make) {
  try {
    make();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Tableau, RejectsWhatIsNotAnExplicitConsistentTableau) {
  EXPECT_EQ(error_of([] {
              Tableau("x", 1, {0, 1, 0, 0}, {0.5, 0.5}, {1, 0});
            }),
            "'a': A must be strictly lower triangular for an explicit method (a[0][1] != 0)");
  EXPECT_EQ(error_of([] {
              Tableau("x", 2, {0, 0, 1, 0}, {0.5, 0.5}, {0, 0.5});
            }),
            "'c': c[1] must equal the sum of row 1 of A");
  EXPECT_EQ(error_of([] {
              Tableau("x", 3, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1});
            }),
            "'order': tableau 'x' declares order 3 but satisfies the order conditions only to order 2 (tree [τ²] of "
            "order 3: Phi = 0.5, 1/gamma = 0.333333333333333, residual 1.667e-01)");
  EXPECT_EQ(error_of([] { Tableau("x", 1, {0, 0, 0}, {1.0}, {0}); }), "'a': A must be 1 x 1");
  EXPECT_EQ(error_of([] { Tableau("x", 1, {}, {}, {}); }), "'a': a tableau needs 1 to 32 stages, got 0");
}

// The stage groups and FSAL come from the coefficients alone: a stage whose
// row of A is b (exactly) at c = 1 is the FSAL stage, whether the error
// weights use it (BS32, DP54) or only the dense output needs it (DP853); F78
// has none.
TEST(Tableau, StageGroupsAndFsalAreDerivedFromTheCoefficients) {
  struct Want {
    Tableau t;
    int stages, attempt, total, fsal, error_order;
  };
  const Want want[] = {{methods::rk4(), 4, 4, 4, -1, 0},
                       {methods::bogacki_shampine32(), 3, 4, 4, 3, 3},
                       {methods::dormand_prince54(), 6, 7, 7, 6, 5},
                       {methods::dormand_prince853(), 12, 12, 16, 12, 8},
                       {methods::fehlberg78(), 13, 13, 13, -1, 8}};
  for (const Want& w : want) {
    SCOPED_TRACE(w.t.name());
    EXPECT_EQ(w.t.stages(), w.stages);
    EXPECT_EQ(w.t.attempt_stages(), w.attempt);
    EXPECT_EQ(w.t.total_stages(), w.total);
    EXPECT_EQ(w.t.fsal_stage().value_or(-1), w.fsal);
    EXPECT_EQ(w.t.error_order(), w.error_order);
    EXPECT_FALSE(w.t.source().empty());
  }
  // Heun with a third stage at y_new: FSAL; the same stage at c = 1 off b is not
  EXPECT_EQ(Tableau("x", 2, {0, 0, 0, 1, 0, 0, 0.5, 0.5, 0}, {0.5, 0.5, 0}, {0, 1, 1}).fsal_stage(), 2);
  EXPECT_FALSE(Tableau("x", 2, {0, 0, 0, 1, 0, 0, 0.25, 0.75, 0}, {0.5, 0.5, 0}, {0, 1, 1}).fsal_stage());
}

TEST(Tableau, EmbeddedWeightsAreCheckedToTheirOrder) {
  // Bogacki-Shampine's e is b_hat - b, as its source gives it; b_hat has order 2, not 3
  TableauCoefficients k = methods::bogacki_shampine32().coefficients();
  k.name = "bs";
  k.embedded_order = 3;
  EXPECT_EQ(error_of([&] { Tableau{k}; }),
            "'e': the embedded weights b - e of tableau 'bs' declare order 3 but satisfy the order conditions "
            "only to order 2 (tree [τ²] of order 3: Phi = 0.291666666666667, 1/gamma = 0.333333333333333, residual "
            "-4.167e-02)");
  k.embedded_order = 2;
  EXPECT_EQ(Tableau(k).error_order(), 3);
  k.e.pop_back();
  EXPECT_EQ(error_of([&] { Tableau{k}; }), "'e': e must have 4 entries");
  k.e.assign(4, 0.0);
  EXPECT_EQ(error_of([&] { Tableau{k}; }), "'e': e is zero: the error estimate would vanish");
  k.e.clear();
  k.e_stretched = {1, 0, 0, 0};
  EXPECT_EQ(error_of([&] { Tableau{k}; }), "'e_stretched': a stretched estimate goes with the embedded weights e");
}

TEST(Tableau, DenseWeightsMustEndAtB) {
  TableauCoefficients k;
  k.name = "heun";
  k.order = 2;
  k.a = {0, 0, 1, 0};
  k.b = {0.5, 0.5};
  k.c = {0, 1};
  k.dense = {1, -0.5, 0, 0.5};  // b_1(theta) = theta - theta^2 / 2, b_2(theta) = theta^2 / 2
  k.dense_order = 2;
  k.dense_degree = 2;
  EXPECT_EQ(Tableau(k).dense_order(), 2);
  k.dense[3] = 0.4;
  EXPECT_EQ(error_of([&] { Tableau{k}; }), "'dense': the dense weights at theta = 1 must equal b (stage 1)");
  k.dense.pop_back();
  EXPECT_EQ(error_of([&] { Tableau{k}; }), "'dense': the dense weights must be 2 x dense_degree");
}

}  // namespace
}  // namespace rb

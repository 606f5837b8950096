#include <gtest/gtest.h>

#include "integrators/tableaus.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

TEST(Tableau, NamedTableausSatisfyTheirOrder) {
  EXPECT_EQ(tableaus::euler().satisfied_order(), 1);
  EXPECT_EQ(tableaus::heun().satisfied_order(), 2);
  EXPECT_EQ(tableaus::kutta3().satisfied_order(), 3);
  EXPECT_EQ(tableaus::rk4().satisfied_order(), 4);
  EXPECT_EQ(tableaus::rk38().satisfied_order(), 4);
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
  EXPECT_EQ(error_of([] { Tableau("x", 1, {0, 1, 0, 0}, {0.5, 0.5}, {1, 0}); }),
            "'a': A must be strictly lower triangular for an explicit method (a[0][1] != 0)");
  EXPECT_EQ(error_of([] { Tableau("x", 2, {0, 0, 1, 0}, {0.5, 0.5}, {0, 0.5}); }),
            "'c': c[1] must equal the sum of row 1 of A");
  EXPECT_EQ(error_of([] { Tableau("x", 3, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1}); }),
            "'order': tableau 'x' declares order 3 but satisfies the order conditions only to order 2 (tree [τ²] of "
            "order 3: Phi = 0.5, 1/gamma = 0.3333333333, residual 1.667e-01)");
  EXPECT_EQ(error_of([] { Tableau("x", 1, {0, 0, 0}, {1.0}, {0}); }), "'a': A must be 1 x 1");
  EXPECT_EQ(error_of([] { Tableau("x", 1, {}, {}, {}); }), "'b': a tableau needs 1 to 16 stages, got 0");
}

}  // namespace
}  // namespace rb

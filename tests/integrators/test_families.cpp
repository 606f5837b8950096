// A family is a folder with a register function and one line in
// integrators/families/families.cpp (docs/extending.md): the registry's
// built-in methods are the families' methods in that order, and a family
// added here, a register function like any folder's, comes through the same
// path (methods_of) as a working integrator.
#include <gtest/gtest.h>

#include "integrators/families/families.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

// the test family's one method: explicit Euler on the flat view, written out
struct EulerStep {
  const Problem& problem;
  FlatState k;
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    stage_flat_rhs(problem, y.data(), k.data(), cost);
    next = y + h * k;
    ++cost.rhs_evals;
  }
};

// what a folder's register_<family>.cpp holds
void register_test_family(MethodList& list) {
  list.push_back(stepped_method({.name = "test-family-euler",
                                 .family = "test-family",
                                 .declared_order = 1,
                                 .controller = "constant",
                                 .description = "explicit Euler, the family test's"},
                                [](const Problem& p) {
                                  return EulerStep{p, {}};
                                }));
}

TEST(Families, TheRegistryStartsWithEveryFamilysMethodsInFamilyOrder) {
  const MethodList builtin = builtin_methods();
  // the first family line's first method, the last line's last
  ASSERT_FALSE(builtin.empty());
  EXPECT_EQ(builtin.front()->name(), "euler");
  EXPECT_EQ(builtin.back()->info().family, "gsl");
  ASSERT_LE(builtin.size(), registry().size());  // then those added at run time
  for (std::size_t i = 0; i < builtin.size(); ++i) EXPECT_EQ(builtin[i]->name(), registry()[i]->name()) << i;
}

TEST(Families, AFamilyAddedByItsRegisterFunctionIsAWorkingMethod) {
  const MethodList methods = methods_of({register_test_family});
  ASSERT_EQ(methods.size(), 1u);
  const Integrator& euler = *methods.front();
  EXPECT_EQ(euler.name(), "test-family-euler");
  EXPECT_EQ(euler.info().family, "test-family");
  // the same steps as the registry's euler, to the bit
  RunOptions options;
  options.t_end = 0.5;
  options.h = 0.01;
  const RunResult mine = euler.integrate(testing::valley(), options);
  const RunResult shipped = find_integrator("euler").integrate(testing::valley(), options);
  EXPECT_EQ(mine.status, Status::ok);
  EXPECT_EQ(mine.cost.steps, 50);
  EXPECT_EQ(mine.final_state, shipped.final_state);
}

}  // namespace
}  // namespace rb

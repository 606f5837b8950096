// A Lie-group method and its flat twin (the same tableau on the flat view)
// agree on the homogeneous ball to rounding (test_munthe_kaas.cpp: R never
// enters G). Where R feeds back they must not: the flat twin's R leaves
// SO(3) and bends the motion through omega = T(R)^-1 v. Checked for every
// twin pair, on the order test's anisotropic scene.
#include <gtest/gtest.h>

#include <string>

#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/order_scene.hpp"

namespace rb {
namespace {

using testing::chaplygin_bowl;

// The twins' contact points differ by more than 1e-10 after 1 s: on the
// homogeneous ball they agree to 1e-12 (test_munthe_kaas.cpp), so a
// difference a hundred times that is R feeding back, not rounding.
void expect_twins_differ(const std::string& lie_name, const std::string& flat_name, double h) {
  const Problem& p = chaplygin_bowl();
  const RunResult lie = testing::run_at(find_integrator(lie_name), p, 1.0, h);
  const RunResult flat = testing::run_at(find_integrator(flat_name), p, 1.0, h);
  ASSERT_EQ(lie.status, Status::ok) << lie_name << ": " << lie.message;
  ASSERT_EQ(flat.status, Status::ok) << flat_name << ": " << flat.message;
  EXPECT_GT(testing::end_errors(p, flat.final_state, lie.final_state).contact, 1e-10)
      << lie_name << " vs " << flat_name << " at h = " << h;
}

TEST(TwinsWhereRFeedsBack, LieGroupAndFlatTwinsDifferInTheContactPoint) {
  // a step per order where both run and their errors are well above rounding
  const struct {
    const char *lie, *flat;
    double h;
  } twins[] = {{"exp-euler", "euler", 0.005},
               {"rkmk2", "heun", 0.01},
               {"rkmk3", "rk3", 0.02},
               {"rkmk4", "rk4", 0.02},
               {"rkmk8", "odeint-fehlberg78", 1.0 / 12}};
  for (const auto& twin : twins) expect_twins_differ(twin.lie, twin.flat, twin.h);
}

}  // namespace
}  // namespace rb

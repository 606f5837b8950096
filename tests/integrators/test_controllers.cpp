// The step-size controllers (integrators/controllers/) against their
// formulas, and chosen per run through RunOptions::controller.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures.hpp"
#include "integrators/controllers/controller.hpp"
#include "integrators/driver.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

using testing::valley;

TEST(Controllers, PiAcceptsWithGustafssonsFormula) {
  FilterController pi(filter_controller("pi"), 5);
  const StepDecision first = pi.decide(0.5, 0.01);
  ASSERT_TRUE(first.accepted);
  // the history starts at 1e-4
  EXPECT_DOUBLE_EQ(first.h_next, 0.01 * 0.9 * std::pow(0.5, -0.7 / 5) * std::pow(1e-4, 0.4 / 5));
  const StepDecision second = pi.decide(0.25, first.h_next);
  EXPECT_DOUBLE_EQ(second.h_next,
                   first.h_next * std::clamp(0.9 * std::pow(0.25, -0.7 / 5) * std::pow(0.5, 0.4 / 5), 0.2, 10.0));
}

TEST(Controllers, RejectionShrinksByTheElementaryRuleAndCapsTheNextGrowth) {
  FilterController pi(filter_controller("pi"), 4);
  const StepDecision rejected = pi.decide(3.0, 0.1);
  EXPECT_FALSE(rejected.accepted);
  EXPECT_DOUBLE_EQ(rejected.h_next, 0.1 * 0.9 * std::pow(3.0, -0.25));
  // a huge error shrinks at most to a fifth
  EXPECT_DOUBLE_EQ(pi.decide(1e12, 0.1).h_next, 0.1 * 0.2);
  // right after a rejection the step may not grow
  const StepDecision after = pi.decide(1e-8, 0.05);
  EXPECT_TRUE(after.accepted);
  EXPECT_DOUBLE_EQ(after.h_next, 0.05);
  // the step after that may, up to tenfold (errors are floored at 1e-10)
  EXPECT_DOUBLE_EQ(pi.decide(1e-12, 0.05).h_next, 0.5);
  EXPECT_DOUBLE_EQ(pi.shrink(0.5), 0.1);
}

TEST(Controllers, IUsesTheLastErrorOnly) {
  FilterController i(filter_controller("i"), 4);
  EXPECT_DOUBLE_EQ(i.decide(0.5, 1.0).h_next, 0.9 * std::pow(0.5, -0.25));
  EXPECT_DOUBLE_EQ(i.decide(0.5, 1.0).h_next, 0.9 * std::pow(0.5, -0.25));
}

TEST(Controllers, PidFiltersTheLastThreeErrors) {
  FilterController pid(filter_controller("pid"), 3);
  const double k = 3;
  auto factor = [&](double e0, double e1, double e2) {
    return 0.9 * std::pow(e0, -1.0 / 18 / k) * std::pow(e1, -1.0 / 9 / k) * std::pow(e2, -1.0 / 18 / k);
  };
  EXPECT_DOUBLE_EQ(pid.decide(0.5, 1.0).h_next, factor(0.5, 1e-4, 1e-4));
  EXPECT_DOUBLE_EQ(pid.decide(0.8, 1.0).h_next, factor(0.8, 0.5, 1e-4));
  EXPECT_DOUBLE_EQ(pid.decide(0.3, 1.0).h_next, factor(0.3, 0.8, 0.5));
}

TEST(Controllers, UnknownNameIsRefusedNamingTheKnownOnes) {
  try {
    (void)filter_controller("p");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "controller");
    EXPECT_NE(std::string(e.what()).find("unknown step-size controller 'p' (known: constant, library, i, pi, pid)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Controllers, OverrideAppliesToFilterControlledMethodsOnly) {
  RunOptions o;
  o.controller = &filter_controller("pid");
  EXPECT_EQ(controller_of("pi", o), "pid");
  EXPECT_EQ(controller_of(kConstantController, o), kConstantController);
  EXPECT_EQ(controller_of(kLibraryController, o), kLibraryController);
  EXPECT_EQ(controller_of("pi", RunOptions{}), "pi");
}

TEST(Controllers, RegistryEntriesKeepTheirControllers) {
  EXPECT_EQ(find_integrator("rkmk4").info().controller, kConstantController);
  EXPECT_EQ(find_integrator("rkmk-dp54-adaptive").info().controller, "pi");
  EXPECT_EQ(find_integrator("odeint-dopri5-adaptive").info().controller, kLibraryController);
  EXPECT_EQ(find_integrator("gsl-rkf45-adaptive").info().controller, kLibraryController);
}

// Every controller meets the tolerance on an RKMK pair; they step
// differently, and the default is PI's.
TEST(Controllers, EachControllerDrivesAnRkmkPairToTheTolerance) {
  const Integrator& pair = find_integrator("rkmk-dp54-adaptive");
  RunOptions o;
  o.t_end = 2.0;
  o.tolerances = Tolerances(1e-8, 1e-8);
  const RunResult by_default = pair.integrate(valley(), o);
  RunOptions fine = o;
  fine.tolerances = Tolerances(1e-12, 1e-12);
  const RunResult reference = pair.integrate(valley(), fine);
  ASSERT_EQ(reference.status, Status::ok);
  long steps[3];
  int n = 0;
  for (const char* name : {"i", "pi", "pid"}) {
    o.controller = &filter_controller(name);
    const RunResult run = pair.integrate(valley(), o);
    ASSERT_EQ(run.status, Status::ok) << name << ": " << run.message;
    EXPECT_LT((run.final_state - reference.final_state).norm(), 1e-6) << name;
    // every stage checked, and the start and the end, and the paths of the
    // steps that moved the contact point more than r/8; the first step's
    // guess (initial_step, 2 evaluations) is not a stage
    EXPECT_EQ(run.cost.validity_checks, run.cost.rhs_evals - 2 + 2 + run.cost.path_checks) << name;
    if (std::string(name) == "pi") {
      EXPECT_EQ(run.cost.steps, by_default.cost.steps);
      EXPECT_EQ(run.final_state, by_default.final_state);
    }
    steps[n++] = run.cost.steps;
  }
  EXPECT_NE(steps[0], steps[2]);
}

}  // namespace
}  // namespace rb

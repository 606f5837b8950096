// The recipe "Add your own integrator" of docs/extending.md, followed by a test: a new way
// of stepping is one stepper (here Ralston's second-order method, which no
// registry entry uses) made into an integrator with stepped_method and one
// registration line. The registry, the runner and the report then treat it
// like any other method, and the driver gives it the same checks and counts.
#include <gtest/gtest.h>

#include "bench/lib/report.hpp"
#include "integrators/controllers/controller.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "tests/integrators/heun_euler.hpp"

namespace rb {
namespace {

// the stepper: y_n+1 = y_n + h (k1 + 3 k2) / 4, k2 = F(y_n + 2/3 h k1)
struct RalstonStep {
  const Problem& problem;
  FlatState k1, k2, mid;
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    stage_flat_rhs(problem, y.data(), k1.data(), cost);
    mid = y + (2.0 / 3.0 * h) * k1;
    stage_flat_rhs(problem, mid.data(), k2.data(), cost);
    next = y + (0.25 * h) * (k1 + 3.0 * k2);
    cost.rhs_evals += 2;
  }
};

std::unique_ptr<Integrator> ralston() {
  return stepped_method({.name = "test-ralston",
                         .family = "rk",
                         .declared_order = 2,
                         .controller = "constant",
                         .description = "Ralston's second-order method (the recipe's test)"},
                        [](const Problem& p) {
                          return RalstonStep{p, {}, {}, {}};
                        });
}

const Integrator& registered() {
  static const bool added = [] {
    add_integrator(ralston(), "test");  // the one registry line
    return true;
  }();
  (void)added;
  return find_integrator("test-ralston");
}

TEST(StepperRecipe, OneStepperAndOneLineMakeAMethodTheRunnerMeasures) {
  const Integrator& method = registered();
  const MethodInfo info = method.info();
  EXPECT_EQ(info.declared_order, 2);
  EXPECT_EQ(info.rotation_order, 2);
  EXPECT_FALSE(info.adaptive);
  EXPECT_EQ(info.controller, kConstantController);

  SweepSpec spec = preset("quick");
  spec.scenes = {"valley-sideways"};
  spec.integrators = {"test-ralston"};
  spec.repeats = 1;
  spec.stability.enabled = false;
  const auto quiet = [](const std::string&) {};
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  const nlohmann::json report = make_report(spec, scenes, run_sweep(spec, scenes, quiet), {});
  ASSERT_EQ(report["runs"].size(), spec.hs.size());
  for (const auto& run : report["runs"]) {
    EXPECT_EQ(run["status"], "ok");
    EXPECT_EQ(run["controller"], "constant");
    EXPECT_EQ(run["rhs_evals"].get<long>(), 2 * run["steps"].get<long>());
    // both stages of every step, the start and the end
    EXPECT_EQ(run["validity_checks"].get<long>(), 2 * run["steps"].get<long>() + 2);
  }
  ASSERT_EQ(report["orders"].size(), 1u);
  EXPECT_NEAR(report["orders"][0]["observed"]["contact"].get<double>(), 2.0, 0.2);
  EXPECT_EQ(report["orders"][0]["pass"], true);
}

// The driver's budget and stop hold for it with no code of its own.
TEST(StepperRecipe, TheDriverStopsItOnTheBudget) {
  RunOptions o;
  o.h = 0.01;
  o.t_end = 1.0;
  o.max_steps = 7;
  const Problem problem = make_problem(load_scene("valley-sideways"));
  const RunResult run = registered().integrate(problem, o);
  EXPECT_EQ(run.status, Status::max_steps);
  EXPECT_EQ(run.message, "reached max_steps = 7");
  EXPECT_EQ(run.cost.steps, 7);
  EXPECT_DOUBLE_EQ(run.stop_time, 0.07);
}

// The tableau half of the recipe: one Tableau (heun_euler.hpp: Heun with
// Euler embedded, which no registry entry uses) and one line per integrator
// naming the tableau, the way of stepping and the controller.
using testing::heun_euler;

TEST(StepperRecipe, OneTableauAndOneLineEachGiveAFixedAndAnAdaptiveMethod) {
  static const bool added = [] {
    add_integrator(rkmk_method(heun_euler(), "test-rkmk-heun-euler", kConstantController), "test");
    add_integrator(rkmk_method(heun_euler(), "test-rkmk-heun-euler-adaptive", "pi"), "test");
    return true;
  }();
  (void)added;
  const Integrator& fixed = find_integrator("test-rkmk-heun-euler");
  const Integrator& adaptive = find_integrator("test-rkmk-heun-euler-adaptive");
  EXPECT_EQ(fixed.family(), "rkmk");
  EXPECT_EQ(fixed.controller(), kConstantController);
  EXPECT_EQ(adaptive.family(), "rkmk-adaptive");
  EXPECT_EQ(adaptive.controller(), "pi");
  EXPECT_TRUE(adaptive.adaptive());

  SweepSpec spec = preset("quick");
  spec.scenes = {"valley-sideways"};
  spec.integrators = {"test-rkmk-heun-euler", "test-rkmk-heun-euler-adaptive"};
  spec.repeats = 1;
  spec.stability.enabled = false;
  const auto quiet = [](const std::string&) {};
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  const nlohmann::json report = make_report(spec, scenes, run_sweep(spec, scenes, quiet), {});
  int fixed_runs = 0, adaptive_runs = 0;
  for (const auto& run : report["runs"]) {
    EXPECT_EQ(run["status"], "ok");
    if (run["integrator"] == "test-rkmk-heun-euler") {
      ++fixed_runs;
      // two stages a step: no error estimate at fixed steps
      EXPECT_EQ(run["rhs_evals"].get<long>(), 2 * run["steps"].get<long>());
    } else {
      ++adaptive_runs;
      EXPECT_EQ(run["controller"], "pi");
    }
  }
  EXPECT_EQ(fixed_runs, static_cast<int>(spec.hs.size()));
  EXPECT_GT(adaptive_runs, 0);
  bool measured = false;
  for (const auto& order : report["orders"])
    if (order["integrator"] == "test-rkmk-heun-euler") {
      EXPECT_NEAR(order["observed"]["contact"].get<double>(), 2.0, 0.2);
      EXPECT_EQ(order["pass"], true);
      measured = true;
    }
  EXPECT_TRUE(measured);
}

}  // namespace
}  // namespace rb

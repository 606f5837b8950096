// The recipe "Add your own integrator" of docs/extending.md followed to the letter by
// integrators/families/rk/explicit_midpoint.hpp (one stepper made an integrator by
// stepped_method, one registry line): the registry, the runner and the report
// pick it up with no other change. The registry-wide tests (order,
// conformance) check it too.
#include <gtest/gtest.h>

#include "bench/lib/report.hpp"
#include "integrators/registry.hpp"

namespace rb {
namespace {

TEST(AddIntegrator, TheReadmeExampleIsPickedUpByTheRunnerAndTheReport) {
  const Integrator& midpoint = find_integrator("midpoint");
  EXPECT_EQ(midpoint.declared_order(), 2);
  EXPECT_FALSE(midpoint.adaptive());

  SweepSpec spec = preset("quick");
  spec.scenes = {"valley-sideways"};
  spec.integrators = {"midpoint"};
  spec.repeats = 1;
  const auto quiet = [](const std::string&) {};
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  const nlohmann::json report = make_report(spec, scenes, run_sweep(spec, scenes, quiet), {});
  ASSERT_EQ(report["runs"].size(), spec.hs.size());
  for (const auto& run : report["runs"]) {
    EXPECT_EQ(run["integrator"], "midpoint");
    EXPECT_EQ(run["status"], "ok");
    EXPECT_EQ(run["rhs_evals"].get<long>(), 2 * run["steps"].get<long>());
  }
  ASSERT_EQ(report["orders"].size(), 1u);
  EXPECT_NEAR(report["orders"][0]["observed"]["contact"].get<double>(), 2.0, 0.2);
  EXPECT_EQ(report["orders"][0]["pass"], true);
}

}  // namespace
}  // namespace rb

// Every registered adaptive integrator, whatever its family: the error falls
// with the tolerance and stays within a factor 100 of it on smooth scenes; a
// tolerance below rounding and a tiny step budget end in statuses, not in a
// crash or an "ok" run. A new adaptive integrator is checked here with no
// new test.
#include <gtest/gtest.h>

#include <map>

#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/registry_names.hpp"

namespace rb {
namespace {

constexpr double kTEnd = 1.0;
// errors below this sit on the reference's and rounding's floor (rkmk4 at
// h = 1e-4 agrees with itself at h = 5e-5 to ~1e-14): no order is seen there
constexpr double kFloor = 1e-12;

const Problem& scene(const std::string& name) {
  static std::map<std::string, Problem> problems;
  auto it = problems.find(name);
  if (it == problems.end()) it = problems.emplace(name, make_problem(load_scene(name))).first;
  return it->second;
}

const FlatState& reference(const std::string& name) {
  static std::map<std::string, FlatState> refs;
  auto it = refs.find(name);
  if (it == refs.end()) {
    RunOptions o;
    o.t_end = kTEnd;
    o.h = 1e-4;
    const RunResult r = find_integrator("rkmk4").integrate(scene(name), o);
    EXPECT_EQ(r.status, Status::ok) << name << ": " << r.message;
    it = refs.emplace(name, r.final_state).first;
  }
  return it->second;
}

RunOptions at_tolerance(double tol) {
  RunOptions o;
  o.t_end = kTEnd;
  o.tolerances = Tolerances(tol, tol);
  return o;
}

std::vector<std::string> adaptive_names() {
  std::vector<std::string> names;
  for (const auto& integrator : registry())
    if (integrator->adaptive()) names.push_back(integrator->name());
  return names;
}

class AdaptiveRegistry : public ::testing::TestWithParam<std::string> {};

TEST_P(AdaptiveRegistry, ErrorFallsWithToleranceAndStaysWithinHundredTimesIt) {
  const Integrator& method = find_integrator(GetParam());
  for (const std::string name : {"valley-sideways", "bowl-3d", "gaussian-hills"}) {
    const Problem& p = scene(name);
    double previous = 0.0;
    for (const double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
      const RunResult r = method.integrate(p, at_tolerance(tol));
      ASSERT_EQ(r.status, Status::ok) << name << " tol " << tol << ": " << r.message;
      const double e = testing::end_errors(p, r.final_state, reference(name)).contact;
      EXPECT_LE(e, 100.0 * tol) << name << " tol " << tol;
      if (previous > 0.0) {
        EXPECT_TRUE(e <= previous || e <= kFloor) << name << " tol " << tol << ": " << e << " after " << previous;
      }
      previous = e;
    }
  }
}

TEST_P(AdaptiveRegistry, ToleranceBelowRoundingEndsInUnderflowOrMaxSteps) {
  const Integrator& method = find_integrator(GetParam());
  RunOptions o = at_tolerance(1e-18);
  o.max_steps = 20'000;  // a controller creeping at tiny steps ends here
  const RunResult r = method.integrate(scene("valley-sideways"), o);
  EXPECT_TRUE(r.status == Status::step_underflow || r.status == Status::max_steps)
      << status_name(r.status) << ": " << r.message;
  EXPECT_LT(r.stop_time, kTEnd);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(r.final_state.allFinite());
}

TEST_P(AdaptiveRegistry, MaxStepsStopsTheRunEarly) {
  const Integrator& method = find_integrator(GetParam());
  RunOptions o = at_tolerance(1e-8);
  o.max_steps = 5;
  const RunResult r = method.integrate(scene("valley-sideways"), o);
  EXPECT_EQ(r.status, Status::max_steps) << r.message;
  EXPECT_LT(r.stop_time, kTEnd);
  EXPECT_LE(r.cost.steps + r.cost.rejected, 5) << "accepted + rejected";
  EXPECT_TRUE(r.final_state.allFinite());
}

INSTANTIATE_TEST_SUITE_P(AdaptiveRegistryAll, AdaptiveRegistry, ::testing::ValuesIn(adaptive_names()),
                         testing::registry_test_name);

}  // namespace
}  // namespace rb

// Validity between the stages of a step (docs/bad-input.md, docs/design.md):
// a loose adaptive step can jump a region beyond the model's limits that
// every one of its stages misses. Near the curvature limit the driver checks
// each accepted step's path (integrators/driver.hpp: check_step_path) and
// keeps steps short enough to resolve the landscape there, so no run ends
// `ok` after its path crossed a limit, whatever its output spacing.
#include <cmath>
#include <string>

#include "integrators/driver.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb::robustness {
namespace {

// Released at rest at (0.3, 0.05) in 7 x^2 + 6 y^2 (r kappa = 1.4 at the
// bottom): the exact path reaches r kappa = 1 near t = 0.423.
constexpr const char* kSteepBowl = "stop-steep-elliptic-bowl.json";

// A flat state of the steep bowl's landscape at contact (x, 0) rolling along
// -x at 3 m/s (a scene's start, so that it is a state of the model).
FlatState rolling_at(double x) {
  const std::string text = R"({"name": "probe", "landscape": "7*x^2 + 6*y^2", "ball": {"radius": 0.1, "mass": 1.0},
      "start": {"contact": [)" +
                           std::to_string(x) + R"(, 0.0], "velocity": [-3.0, 0.0]}, "t_end": 1.0})";
  return make_problem(parse_scene(text)).y0();
}

// The issue's case: rkmk-f78-adaptive at rtol = atol = 1e-2 ended `ok` with
// one output at t = 1 (energy error 3.8 J of 6.55) and stopped with
// `curvature` with outputs every 0.01. Every adaptive method, at a loose and a
// moderate tolerance, with one output and with outputs every 0.1, now stops
// with `curvature` where the exact path does. gsl-msbdf-adaptive is left out:
// at rtol >= 1e-3 its own path (energy error 3.3 J) never comes within
// 3.5 cm of the bottom, so there is no crossing of a computed path to find
// (docs/bad-input.md says so).
TEST(StepPaths, LooseAdaptiveRunsStopAtTheCurvatureLimitForEveryOutputSpacing) {
  const Problem p = data_problem(kSteepBowl);
  int runs = 0;
  for (const auto& m : registry()) {
    if (!m->adaptive() || m->name() == "gsl-msbdf-adaptive") continue;
    for (const double tol : {1e-2, 1e-5}) {
      for (const double dt : {1.0, 0.1}) {
        const RunResult r = m->integrate(p, options_for(*m, 1.0, 0.0, tol, dt));
        SCOPED_TRACE(m->name() + " tol " + std::to_string(tol) + " dt-out " + std::to_string(dt));
        EXPECT_EQ(status_name(r.status), status_name(Status::curvature)) << r.message;
        EXPECT_GT(r.stop_time, 0.41);
        EXPECT_LT(r.stop_time, 0.44);
        ++runs;
      }
    }
  }
  EXPECT_GE(runs, 4 * 20);
}

// The path from (0.1, 0) to (-0.1, 0) crosses the bottom, where r kappa =
// 1.4; both ends fit the ball (r kappa = 0.28). The path check finds the
// curvature limit between them; the path from (0.2, 0) to (0.1, 0) stays
// where the ball fits and is checked at one point per quarter radius of
// contact travel (at least three).
TEST(StepPaths, TheHermitePathFindsARegionBetweenTheEnds) {
  const Problem p = data_problem(kSteepBowl);
  const FlatState a = rolling_at(0.1), b = rolling_at(-0.1), c = rolling_at(0.2);
  ASSERT_EQ(p.check_full(a).status, Status::ok);
  ASSERT_EQ(p.check_full(b).status, Status::ok);
  Cost cost;
  const PathCheck across = check_step_path(p, a, b, 0.2 / 3.0, cost);
  EXPECT_EQ(status_name(across.limit.status), status_name(Status::curvature)) << across.limit.reason;

  Cost inside_cost;
  const PathCheck inside = check_step_path(p, c, a, 0.1 / 3.0, inside_cost);
  EXPECT_EQ(inside.limit.status, Status::ok) << inside.limit.reason;
  EXPECT_GE(inside.travel, 0.1);  // at least the chord
  const long points = static_cast<long>(std::ceil(inside.travel / 0.025));
  EXPECT_EQ(inside_cost.validity_checks, 2 + std::max<long>(kPathPointsMin, points));
}

// A run that never comes near a limit pays nothing for this: its validity
// checks are its stages' and the start's and end's, as before.
TEST(StepPaths, RunsFarFromTheLimitsCheckNoPath) {
  const Problem p = make_problem(load_scene("valley-sideways"));
  const Integrator& m = find_integrator("rk-dp54-adaptive");
  const RunResult r = m.integrate(p, options_for(m, 2.0, 0.0, 1e-8, 0.5));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_FALSE(r.cost.watch.near);
  // every stage is checked, and the start and the end once each; the two
  // evaluations of the first-step guess are not
  EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals - 2 + 2);
}

// Only the adaptive driver reads whether a stage came near the curvature
// limit (Cost::watch.near), so the fixed-step RKMK stages leave that test out
// (RkmkStepper's step<false>): on the steep bowl, which both runs pass r kappa =
// 1/2 on, the adaptive run records it, rkmk4 does not and still stops at the
// curvature limit where the exact path reaches it.
TEST(StepPaths, OnlyTheAdaptiveRunsWatchForTheCurvatureLimitsApproach) {
  const Problem p = data_problem(kSteepBowl);
  const Integrator& adaptive = find_integrator("rkmk-dp54-adaptive");
  const RunResult a = adaptive.integrate(p, options_for(adaptive, 1.0, 0.0, 1e-8, 0.1));
  EXPECT_EQ(status_name(a.status), status_name(Status::curvature)) << a.message;
  EXPECT_TRUE(a.cost.watch.near);
  const Integrator& fixed = find_integrator("rkmk4");
  const RunResult f = fixed.integrate(p, options_for(fixed, 1.0, 1e-3, 0.0, 0.1));
  EXPECT_EQ(status_name(f.status), status_name(Status::curvature)) << f.message;
  EXPECT_GT(f.stop_time, 0.41);
  EXPECT_LT(f.stop_time, 0.44);
  EXPECT_FALSE(f.cost.watch.near);
}

}  // namespace
}  // namespace rb::robustness

// The model's limits checked at every step (docs/model.md, "Where the
// model stops holding"), not only at outputs: a run that crosses a limit
// between two outputs stops at the step where it happens, and a start
// beyond a limit is bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

// The issue's example: released at (0.3, 0) on 6 (x^2 + y^2), r kappa = 1.2
// at the bottom; the ball rolls through the bottom long before t = 1.
Problem steep_bowl() {
  return make_problem(parse_scene(R"js({"name": "steep-bowl", "landscape": "6*(x^2 + y^2)",
    "ball": {"radius": 0.1, "mass": 1.0}, "start": {"contact": [0.3, 0.0], "omega": [0, 0, 0]}, "t_end": 1.0})js"));
}

Problem lift_off_crest() { return make_problem(load_scene(std::string(RB_TEST_DATA) + "/stop-lift-off.json")); }

RunOptions end_only(const Integrator& method, double t_end, double h) {
  RunOptions o;
  o.t_end = t_end;
  o.h = method.adaptive() ? 0.0 : h;
  o.tolerances = Tolerances(1e-9, 1e-9);
  return o;
}

// Stops with the status between outputs (only t_end is one), keeping no
// row, and the last valid state is within the model.
void expect_stop_between_outputs(const Problem& p, Status want) {
  for (const char* name : {"euler", "rk4", "rkmk4", "rk4-projected", "rk4-quaternion", "odeint-rk4", "gsl-rk4",
                           "odeint-dopri5-adaptive", "gsl-rkf45-adaptive", "rkmk-dp54-adaptive", "gsl-rk4imp"}) {
    const Integrator& m = find_integrator(name);
    const RunResult r = m.integrate(p, end_only(m, p.t_end(), 1e-3));
    EXPECT_EQ(status_name(r.status), status_name(want)) << name << ": " << r.message;
    EXPECT_NE(r.message.find(" at t = "), std::string::npos) << name << ": " << r.message;
    EXPECT_GT(r.stop_time, 0.0) << name;
    EXPECT_LT(r.stop_time, p.t_end()) << name;
    EXPECT_TRUE(r.output.t.empty()) << name;
    EXPECT_EQ(p.check_full(r.final_state).status, Status::ok) << name;
  }
}

TEST(ValidityEveryStep, CurvatureCrossedBetweenOutputsStops) {
  expect_stop_between_outputs(steep_bowl(), Status::curvature);
}

TEST(ValidityEveryStep, LiftOffCrossedBetweenOutputsStops) {
  expect_stop_between_outputs(lift_off_crest(), Status::lift_off);
}

// The stop is at the step where the limit is crossed: the state one step
// later is beyond it, and a run ending at the stop time is ok.
TEST(ValidityEveryStep, StopIsAtTheCrossingStep) {
  const Problem p = steep_bowl();
  const double h = 1e-3;
  for (const char* name : {"rk4", "rkmk4", "odeint-rk4", "gsl-rk4"}) {
    const Integrator& m = find_integrator(name);
    const RunResult r = m.integrate(p, end_only(m, 1.0, h));
    ASSERT_EQ(r.status, Status::curvature) << name << ": " << r.message;
    const long steps = std::lround(r.stop_time / h);
    EXPECT_NEAR(r.stop_time, steps * h, 1e-12) << name;
    const RunResult upto = m.integrate(p, end_only(m, steps * h, h));
    EXPECT_EQ(upto.status, Status::ok) << name << ": " << upto.message;
    EXPECT_EQ(upto.final_state, r.final_state) << name;
    const RunResult one_more = m.integrate(p, end_only(m, (steps + 1) * h, h));
    EXPECT_EQ(one_more.status, Status::curvature) << name;
    EXPECT_DOUBLE_EQ(one_more.stop_time, r.stop_time) << name;
    const double r_kappa = p.model().margins_at(r.final_state).r_kappa_max();
    EXPECT_LT(r_kappa, 1.0) << name;
    EXPECT_GT(r_kappa, 0.9) << name;
  }
}

// How the checks are counted (every stage's evaluation): see
// test_validity_every_stage.cpp, EvaluationsCountedPerStepAreTheMethodsOwn.

TEST(ValidityEveryStep, StartBeyondALimitIsBadInput) {
  // no gravity on a plane: no normal force at all
  try {
    parse_scene(R"({"name": "w", "landscape": "0", "gravity": 0, "ball": {"radius": 0.1, "mass": 1.0},
      "start": {"contact": [0, 0], "omega": [1, 0, 0]}, "t_end": 1})");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "start");
    EXPECT_NE(std::string(e.what()).find("normal force"), std::string::npos) << e.what();
  }
  // at the bottom of the steep bowl r kappa = 1.2
  try {
    parse_scene(R"js({"name": "b", "landscape": "6*(x^2 + y^2)", "ball": {"radius": 0.1, "mass": 1.0},
      "start": {"contact": [0, 0], "omega": [0, 0, 0]}, "t_end": 1})js");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "start.contact");
    EXPECT_NE(std::string(e.what()).find("r * max curvature = 1.2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rb

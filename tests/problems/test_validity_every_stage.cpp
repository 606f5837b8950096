// The model's limits tested at every stage a step evaluates (docs/design.md,
// "Validity at every stage"): on a bowl the ball cannot roll through
// (r kappa = 1.2 at the bottom) steps of h >= 0.01 jump across the whole
// region where r kappa > 1 between two accepted states, so only a stage
// sees it. Every family stops there with curvature, its rows kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/scene.hpp"

namespace rb {
namespace {

Problem steep_bowl() { return make_problem(load_scene(std::string(RB_TEST_DATA) + "/stop-steep-bowl.json")); }

// outputs every dt up to t_end = 1, as `rollbench trajectory --dt-out dt`
RunOptions outputs_every(double dt) {
  RunOptions o;
  o.t_end = 1.0;
  for (int k = 1; k * dt < 1.0 - 1e-12; ++k) o.output_times.push_back(k * dt);
  return o;
}

// curvature, stopped before t_end at a state within the model, with every
// output row up to the stop kept and each of them within the model too
void expect_curvature_stop(const Problem& p, const RunOptions& o, const RunResult& r, const std::string& what) {
  ASSERT_EQ(status_name(r.status), "curvature") << what << ": " << r.message;
  // r kappa reached 1, or (met first by an adaptive step creeping up to
  // the limit) E singular, which happens at the same place
  EXPECT_NE(r.message.find(" at t = "), std::string::npos) << what << ": " << r.message;
  EXPECT_GT(r.stop_time, 0.0) << what;
  EXPECT_LT(r.stop_time, 1.0) << what;
  EXPECT_EQ(p.check_full(r.final_state).status, Status::ok) << what;
  std::size_t reached = 0;
  for (double t : o.output_times) reached += t <= r.stop_time ? 1 : 0;
  EXPECT_EQ(r.output.t.size(), reached) << what << " stopped at " << r.stop_time;
  EXPECT_GT(r.output.t.size(), 0u) << what;
  for (const FlatState& y : r.output.y) EXPECT_EQ(p.check_full(y).status, Status::ok) << what;
}

// One fixed-step method per family, at the steps the issue found crossing.
// GSL's implicit fixed step gets a Newton tolerance of 1e-8: at its
// default of 1e-13 the solve fails near the bottom before any iterate
// reaches the limit (an error, not a crossing).
TEST(ValidityEveryStage, FixedStepMethodsStopAtTheCrossing) {
  const Problem p = steep_bowl();
  for (const char* name : {"rk4", "rk3", "rkmk4", "rkmk4-cayley", "cf4", "cg4a", "rk4-projected", "rk4-quaternion",
                           "odeint-rk4", "odeint-dopri5", "odeint-abm4", "gsl-rk4", "gsl-rkf45", "gsl-rk4imp"}) {
    for (const double h : {0.01, 0.02, 0.05}) {
      RunOptions o = outputs_every(std::max(0.01, h));
      o.h = h;
      if (std::string(name).ends_with("imp")) o.tolerances = Tolerances(1e-8, 1e-8);
      const RunResult r = find_integrator(name).integrate(p, o);
      expect_curvature_stop(p, o, r, std::string(name) + " h = " + std::to_string(h));
    }
  }
}

// One adaptive method per family at tol 1e-2: a stage beyond the limit
// rejects the step, which shrinks until the limit is met at the smallest step.
TEST(ValidityEveryStage, AdaptiveMethodsStopAtTheCrossing) {
  const Problem p = steep_bowl();
  RunOptions o = outputs_every(0.01);
  o.tolerances = Tolerances(1e-2, 1e-2);
  const auto flat_pair = rk_method(methods::dormand_prince54(), "rk-dp54-adaptive", "pi");
  std::vector<const Integrator*> methods = {flat_pair.get()};
  for (const char* name : {"rkmk-dp54-adaptive", "rkmk-f78-adaptive", "cg3-adaptive", "odeint-dopri5-adaptive",
                           "odeint-cash-karp54-adaptive", "odeint-bulirsch-stoer", "gsl-rkf45-adaptive",
                           "gsl-rk8pd-adaptive", "gsl-rk4imp-adaptive", "gsl-bsimp-adaptive", "gsl-msbdf-adaptive"})
    methods.push_back(&find_integrator(name));
  for (const Integrator* m : methods) {
    const RunResult r = m->integrate(p, o);
    expect_curvature_stop(p, o, r, m->name());
    // it got there by shrinking: steps refused at the limit
    EXPECT_GT(r.cost.rejected, 0) << m->name();
  }
}

// Every evaluation a step makes is checked: no method pays an evaluation
// the count leaves out, and an FSAL method's evaluations per step differ
// from a first-stage method's only by what its own stages say (odeint's
// dopri5: 7 stages, 6 evaluations a step; cash-karp54: 6 stages, 6).
TEST(ValidityEveryStage, EvaluationsCountedPerStepAreTheMethodsOwn) {
  const Problem p = make_problem(load_scene("valley-sideways"));
  RunOptions o = outputs_every(0.1);
  o.h = 0.01;
  struct Want {
    const char* name;
    long per_step;  // evaluations a step, after a start of its own
  };
  for (const Want w :
       {Want{"rk4", 4}, Want{"rkmk4", 4}, Want{"rk4-projected", 4}, Want{"rk4-quaternion", 4}, Want{"odeint-rk4", 4},
        Want{"odeint-cash-karp54", 6}, Want{"odeint-dopri5", 6}, Want{"gsl-rk4", 11}, Want{"cf4", 4}}) {
    const RunResult r = find_integrator(w.name).integrate(p, o);
    ASSERT_EQ(r.status, Status::ok) << w.name;
    ASSERT_EQ(r.cost.steps, 100) << w.name;
    // the stages' checks, and one evaluation each at the start and the end
    EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals + 2) << w.name;
    // dopri5's first step evaluates its first stage once more than FSAL steps
    EXPECT_LE(std::abs(r.cost.rhs_evals - w.per_step * r.cost.steps), 1) << w.name << " " << r.cost.rhs_evals;
  }
  // adaptive: every evaluation of every attempt, rejected ones too (a first
  // step given, so that no starting guess evaluates)
  RunOptions a = outputs_every(0.1);
  a.h = 1e-3;
  a.tolerances = Tolerances(1e-8, 1e-8);
  for (const char* name :
       {"odeint-cash-karp54-adaptive", "gsl-rkf45-adaptive", "gsl-rk4imp-adaptive", "cg3-adaptive"}) {
    const RunResult r = find_integrator(name).integrate(p, a);
    ASSERT_EQ(r.status, Status::ok) << name;
    // and the paths of its steps that moved the contact point more than r/8
    EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals + 2 + r.cost.path_checks) << name;
  }
  // with a dense output, also each output row it interpolates (9 here)
  for (const char* name : {"rkmk-dp54-adaptive", "odeint-dopri5-adaptive"}) {
    const RunResult r = find_integrator(name).integrate(p, a);
    ASSERT_EQ(r.status, Status::ok) << name;
    EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals + 2 + 9 + r.cost.path_checks) << name;
  }
}

}  // namespace
}  // namespace rb

// cg3-adaptive: cg3 with the embedded order-2 weights of Engo and
// Marthinsen. The weights against their order conditions, R on SO(3), the
// error falling with the tolerance on a closed-form scene and where R feeds
// back, and the counts of an attempt. The one stepper: a pair's step is its
// fixed method's bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/exp_product/cf4.hpp"
#include "integrators/families/exp_product/cg3.hpp"
#include "integrators/families/exp_product/exp_product.hpp"
#include "integrators/families/exp_product/exp_product_stepper.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::valley;

const Problem& scene(const char* name) { return testing::shipped_scene(name); }

// rtol = atol = tol to t_end, an output every dt
RunOptions tolerance(double tol, double t_end, double dt) { return testing::tolerance_every(tol, dt, t_end); }

// one field per exponential: the weight of each factor
std::vector<double> weights_of(const ExpProduct& p) {
  std::vector<double> w;
  for (const FieldSum& f : p) w.push_back(f.back());
  return w;
}

TEST(CgAdaptive, EmbeddedWeightsHaveOrderTwoAndNotThree) {
  const ExpProductScheme s = methods::cg3_pair();
  ASSERT_EQ(s.stages.size(), 3u);
  std::vector<double> c = {0.0};
  for (std::size_t i = 1; i < s.stages.size(); ++i) {
    double ci = 0.0;
    for (double a : weights_of(s.stages[i])) ci += a;
    c.push_back(ci);
  }
  EXPECT_NEAR(c[1], 3.0 / 4, 1e-15);
  EXPECT_NEAR(c[2], 17.0 / 24, 1e-15);
  auto moment = [&](const std::vector<double>& b, int k) {
    double sum = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) sum += b[i] * std::pow(c[i], k);
    return sum;
  };
  const std::vector<double> high = weights_of(s.update), low = weights_of(s.embedded);
  for (const auto& b : {high, low}) {
    EXPECT_NEAR(moment(b, 0), 1.0, 1e-14);
    EXPECT_NEAR(moment(b, 1), 0.5, 1e-14);
  }
  EXPECT_NEAR(moment(high, 2), 1.0 / 3, 1e-14);
  EXPECT_NEAR(moment(low, 2), 229.0 / 384, 1e-14);  // not 1/3: the estimate is O(h^3)
  EXPECT_EQ(s.embedded_order, 2);
  EXPECT_EQ(s.order, 3);
}

// cf4_pair's embedded update as a method of its own (5 stages, fixed step),
// the order its comment derives; with its two exponentials the other way
// round the commutator term has the wrong sign and R loses an order
std::unique_ptr<Integrator> cf4_embedded(bool reversed_exponentials) {
  ExpProductScheme low = methods::cf4_pair();
  low.update = low.embedded;
  if (reversed_exponentials) std::swap(low.update[0], low.update[1]);
  low.order = 3;
  low.embedded.clear();
  low.embedded_order = 0;
  low.name = "cf4-embedded";
  return exp_product_method(low, low.name, kConstantController);
}

TEST(CfAdaptive, Cf4sEmbeddedUpdateHasOrderThreeWhereRFeedsBack) {
  const Problem& p = scene("chaplygin-valley");
  RunOptions fine;
  fine.t_end = 1.0;
  fine.h = 5e-5;
  const FlatState ref = find_integrator("rkmk4").integrate(p, fine).final_state;
  const testing::Convergence c = testing::measure_convergence(*cf4_embedded(false), p, 1.0, ref);
  ASSERT_GE(c.contact_fit.points, 3);
  EXPECT_NEAR(c.contact_fit.slope, 3.0, 0.25);
  EXPECT_NEAR(c.omega_fit.slope, 3.0, 0.25);
  EXPECT_NEAR(c.rotation_fit.slope, 3.0, 0.25);
  const testing::Convergence wrong = testing::measure_convergence(*cf4_embedded(true), p, 1.0, ref);
  EXPECT_NEAR(wrong.rotation_fit.slope, 2.0, 0.25);
}

TEST(CfAdaptive, RegisteredWithAnExtraStageAndErrorFallingWithTheTolerance) {
  const Integrator& m = find_integrator("cf4-adaptive");
  EXPECT_TRUE(m.adaptive());
  EXPECT_EQ(m.declared_order(), 4);
  const Problem& p = scene("chaplygin-valley");
  RunOptions fine;
  fine.t_end = 1.0;
  fine.h = 5e-5;
  const FlatState ref = find_integrator("rkmk4").integrate(p, fine).final_state;
  double previous = 1.0;
  for (double tol : {1e-5, 1e-7, 1e-9}) {
    const RunResult run = m.integrate(p, tolerance(tol, 1.0, 1.0));
    ASSERT_EQ(run.status, Status::ok) << run.message;
    const double error = (run.final_state - ref).cwiseAbs().maxCoeff();
    EXPECT_LT(error, 100 * tol) << tol;
    EXPECT_LT(error, previous) << tol;
    previous = error;
  }
}

TEST(CgAdaptive, RegisteredAsAdaptiveCrouchGrossman) {
  const Integrator& m = find_integrator("cg3-adaptive");
  EXPECT_TRUE(m.adaptive());
  EXPECT_EQ(m.family(), "cg-adaptive");
  EXPECT_EQ(m.controller(), "pi");
  EXPECT_EQ(m.declared_order(), 3);
}

TEST(CgAdaptive, RefusesASchemeWithoutAnEmbeddedUpdate) {
  try {
    (void)exp_product_method(methods::cg3(), "cg3", "pi");
    FAIL() << "accepted cg3 without an embedded update";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "cg3: an adaptive method needs an embedded update and its order");
  }
}

TEST(CgAdaptive, RotationStaysOnSO3) {
  for (const char* name : {"valley-sideways", "chaplygin-valley"}) {
    const RunResult run = find_integrator("cg3-adaptive").integrate(scene(name), tolerance(1e-8, 2.0, 0.01));
    ASSERT_EQ(run.status, Status::ok) << name << ": " << run.message;
    ASSERT_GT(run.output.y.size(), 150u);
    double worst = 0.0;
    for (const FlatState& y : run.output.y) worst = std::max(worst, rotation_defect(rotation_of(y)));
    EXPECT_LT(worst, 1e-13) << name;
  }
}

// the error at t_end: the contact and the rotation angle (against a state)
double error_against(const FlatState& y, const Vec2& alpha, const Mat3& R) {
  return std::max((contact_of(y) - alpha).norm(), rotation_angle_between(rotation_of(y), R));
}

double closed_form_error(double tol) {
  const Problem& p = scene("bowl-planar");
  const RunResult run = find_integrator("cg3-adaptive").integrate(p, tolerance(tol, 2.0, 2.0));
  EXPECT_EQ(run.status, Status::ok) << run.message;
  const ExactState e = p.exact()->at(2.0);
  EXPECT_TRUE(e.has_rotation);
  return error_against(run.final_state, e.alpha, e.R);
}

double anisotropic_error(double tol) {
  const Problem& p = scene("chaplygin-valley");
  RunOptions fine;
  fine.t_end = 1.0;
  fine.h = 5e-5;
  static const FlatState ref = find_integrator("rkmk4").integrate(p, fine).final_state;
  const RunResult run = find_integrator("cg3-adaptive").integrate(p, tolerance(tol, 1.0, 1.0));
  EXPECT_EQ(run.status, Status::ok) << run.message;
  return error_against(run.final_state, contact_of(ref), rotation_of(ref));
}

// The controller holds the order-2 estimate, O(h^3), at tol, while the
// propagated order-3 step errs O(h^4): a global error ~ tol^(4/3) / h ~
// tol^1 (local extrapolation). 100x in tol: 100x in error, at least 10x.
TEST(CgAdaptive, ErrorFallsWithTheTolerance) {
  for (const auto& [what, error] : {std::pair{"bowl-planar (closed form)", &closed_form_error},
                                    std::pair{"chaplygin-valley", &anisotropic_error}}) {
    const double e6 = error(1e-6), e8 = error(1e-8);
    std::printf("  %-26s error at tol 1e-6: %.3g, at 1e-8: %.3g (exponent %.2f)\n", what, e6, e8,
                std::log10(e6 / e8) / 2);
    EXPECT_GT(e6 / e8, 10.0) << what;
    EXPECT_NEAR(std::log10(e6 / e8) / 2, 1.0, 0.2) << what;
    EXPECT_LT(e6, 100 * 1e-6) << what;
    EXPECT_LT(e8, 100 * 1e-8) << what;
  }
}

// per attempt: 2 rhs (stages 2, 3), 3 + 3 exponentials for the two updates
// and, where R feeds back, 1 + 2 for the stage orientations; the first
// stage once per accepted step (h given: no rhs for a first step)
TEST(CgAdaptive, CountsRhsAndExponentialsPerAttempt) {
  for (const auto& [name, exps] : {std::pair{"valley-sideways", 6L}, std::pair{"chaplygin-valley", 9L}}) {
    RunOptions o = tolerance(1e-7, 1.0, 0.1);
    o.h = 1e-3;
    const RunResult run = find_integrator("cg3-adaptive").integrate(scene(name), o);
    ASSERT_EQ(run.status, Status::ok) << run.message;
    const long attempts = run.cost.steps + run.cost.rejected;
    EXPECT_GT(run.cost.steps, 10) << name;
    EXPECT_EQ(run.cost.exp_evals, exps * attempts) << name;
    EXPECT_EQ(run.cost.rhs_evals, 2 * attempts + run.cost.steps) << name;
    EXPECT_EQ(run.cost.dexpinv_evals, 0) << name;
    EXPECT_EQ(run.cost.validity_checks, run.cost.rhs_evals + 2) << name;  // every stage, the start, the end
  }
}

// The one stage loop: an attempt of the pair (step<true>) and the fixed
// step of the scheme without its embedded update (step<false>) give the
// same new state bit for bit, step after step, where R feeds back
// (chaplygin-valley: stage orientations) and where it does not.
TEST(ExpProductStepper, PairsStepIsTheFixedStepBitForBit) {
  const std::pair<ExpProductScheme, ExpProductScheme> schemes[] = {{methods::cf4(), methods::cf4_pair()},
                                                                   {methods::cg3(), methods::cg3_pair()}};
  for (const auto& [fixed_scheme, pair_scheme] : schemes)
    for (const char* name : {"valley-sideways", "chaplygin-valley"}) {
      const Problem& p = scene(name);
      const ExpPlan fixed_plan = plan_of(fixed_scheme), pair_plan = plan_of(pair_scheme);
      ExpProductStepper fixed(p, fixed_plan);
      ExpProductStepper pair(p, pair_plan, Tolerances(1e-8, 1e-8));
      Cost fixed_cost, pair_cost;
      FlatState y = p.y0(), next = y, paired = y;
      double t = 0.0;
      for (int n = 0; n < 20; ++n) {
        const double h = 0.01 * (1.0 + 0.1 * n);  // steps of changing size, as a controller takes them
        fixed(y, next, t, h, fixed_cost);
        const double err = pair.try_step(t, h, pair_cost);
        ASSERT_TRUE(std::isfinite(err)) << name;
        EXPECT_GT(err, 0.0) << name;  // the estimate was computed
        pair.accept(t, h, pair_cost);
        pair.state(paired);
        ASSERT_TRUE((paired.array() == next.array()).all())
            << pair_scheme.name << "'s pair on " << name << ", step " << n << ": " << (paired - next).transpose();
        y = next;
        t += h;
      }
      // the pair's extra work: cf4_pair's fifth stage, the embedded update
      EXPECT_EQ(pair_cost.rhs_evals - fixed_cost.rhs_evals, 20 * (pair_plan.stages - fixed_plan.stages)) << name;
      EXPECT_GT(pair_cost.exp_evals, fixed_cost.exp_evals) << name;
    }
}

// A pair's scheme at constant steps computes only the stages its update
// reads: cf4_pair's fifth stage (for the embedded update) is left out, so it
// is cf4, results and counts.
TEST(ExpProductStepper, PairSchemeAtConstantStepsIsItsFixedMethod) {
  const std::unique_ptr<Integrator> m = exp_product_method(methods::cf4_pair(), "cf4-pair", kConstantController);
  EXPECT_FALSE(m->adaptive());
  EXPECT_EQ(m->description().rfind("4-stage commutator-free method", 0), 0u) << m->description();
  EXPECT_EQ(exponentials_per_step(methods::cf4_pair(), true), exponentials_per_step(methods::cf4(), true));
  const Problem& p = scene("chaplygin-valley");
  const RunResult a = m->integrate(p, testing::fixed(0.01, 1.0));
  const RunResult b = find_integrator("cf4").integrate(p, testing::fixed(0.01, 1.0));
  ASSERT_EQ(a.status, Status::ok) << a.message;
  EXPECT_TRUE((a.final_state.array() == b.final_state.array()).all()) << (a.final_state - b.final_state).transpose();
  EXPECT_EQ(a.cost.rhs_evals, 4 * a.cost.steps);
  EXPECT_EQ(a.cost.rhs_evals, b.cost.rhs_evals);
  EXPECT_EQ(a.cost.exp_evals, b.cost.exp_evals);
}

}  // namespace
}  // namespace rb

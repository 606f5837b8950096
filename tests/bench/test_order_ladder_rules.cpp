// The rules that let more order fits reach a verdict without deciding one
// wrongly (docs/usage.md, "Orders"): each component is fitted above its own
// floor, the self-convergence slope is read over the reference window's
// steps, a wide interval whose slopes still move asks for finer steps, and
// so does a ladder whose runs failed where a smaller step may run.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bench/lib/finer_steps.hpp"
#include "bench/lib/fit_run.hpp"
#include "bench/lib/group_orders.hpp"
#include "bench/lib/order_fit.hpp"
#include "tests/bench/error_series.hpp"

namespace rb {
namespace {

std::size_t component(const std::string& name) {
  for (std::size_t i = 0; i < kErrorComponentCount; ++i)
    if (name == kErrorComponents[i].name) return i;
  return kErrorComponentCount;
}

// A run at h whose every component errs e(h), listed below_floor where
// e(h) < floor; ok false: a run that failed, without errors.
template <class F>
FitRun run_erring(double h, F&& e, double floor, int declared, bool ok = true) {
  FitRun r;
  r.h = h;
  r.ok = ok;
  r.stop_time = 5.0;
  r.declared_order = r.declared_rotation_order = declared;
  r.end.alpha = Vec2::Zero();
  r.end.centre = Vec3::Zero();
  r.end.omega = Vec3::Zero();
  r.end.R = Mat3::Identity();
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    if (!ok) continue;
    if (e(h) < floor) {
      r.error.below_floor.push_back(kErrorComponents[i].name);
    } else {
      r.error.component(i) = e(h);
    }
  }
  return r;
}

std::vector<const FitRun*> pointers(const std::vector<FitRun>& runs) {
  std::vector<const FitRun*> out;
  for (const FitRun& r : runs) out.push_back(&r);
  return out;
}

TEST(OrderLadderRules, TheRoundingIsMeasuredAtTheReferencesFinerStep) {
  // the floors are the disagreement of the reference and its check, which
  // takes half the reference's step: there the rounding was measured
  EXPECT_DOUBLE_EQ(kReferenceRoundingStep, ReferenceSettings{}.h / 2);
  EXPECT_DOUBLE_EQ(OrderScale{}.rounding_step, kReferenceRoundingStep);
}

TEST(OrderLadderRules, EachComponentIsFittedAboveItsOwnFloor) {
  // an order-8 method, 10 h^8 at every component, on a scene whose omega
  // floor is 1e-12 (the largest, the report's "error") while the contact
  // point's reference errs 1e-15: the contact point fits two decades more
  const double overall = 1e-12;
  const auto e = [](double x) { return 10 * std::pow(x, 8); };
  std::vector<FitRun> runs;
  for (double h : ladder(10)) runs.push_back(run_erring(h, e, overall, 8));
  OrderScale scale{overall, 1.0};
  const std::size_t contact = component("contact"), omega = component("omega");
  scale.component_floor.fill(overall);
  scale.component_floor[contact] = 1e-15;
  const auto orders = group_orders(pointers(runs), scale);
  const OrderFit& fine = orders[contact].reference;
  const OrderFit& coarse = orders[omega].reference;
  // every fitted error at least 100x its own floor, and a lower h_min there
  EXPECT_GE(e(fine.h_min), 100 * 1e-15);
  EXPECT_LT(e(fine.h_min), 100 * overall);
  EXPECT_GE(e(coarse.h_min), 100 * overall);
  EXPECT_LT(fine.h_min, coarse.h_min);
  EXPECT_NEAR(fine.slope, 8.0, 0.05);
  // a run below the overall floor has no value: it counts on the plateau,
  // never fitted, whatever the component's own floor
  EXPECT_GT(fine.at_floor, 0);
  for (const FitRun& r : runs) {
    if (!r.error.below_floor.empty()) {
      EXPECT_LT(r.h, fine.h_min);
    }
  }
  // a report without per-component floors fits every component above the overall one
  const auto old = group_orders(pointers(runs), OrderScale{overall, 1.0});
  EXPECT_DOUBLE_EQ(old[contact].reference.h_min, coarse.h_min);
}

TEST(OrderLadderRules, TheSelfConvergenceSlopeIsReadOverTheReferenceWindow) {
  // heun on chaplygin-valley: order 2 at the smallest steps, where the
  // reference window sits (2^-15 .. 2^-12); above them a steeper
  // pre-asymptotic stretch that the distances' own window, one halving
  // higher, takes in
  std::vector<double> h;
  for (int k = 6; k <= 15; ++k) h.push_back(std::ldexp(1.0, -k));
  const double knee = std::ldexp(1.0, -12);
  const auto e = [&](double x) { return x * x * (x > knee ? std::pow(x / knee, 2) : 1.0); };
  const OrderFit reference = fit_order(h, errors(h, e), 1e-16, 0.1, 8, 0.0);
  ASSERT_DOUBLE_EQ(reference.h_max, knee);
  ASSERT_EQ(order_verdict(reference, 2), "as declared");
  std::vector<double> self_h, self_d;
  for (double x : h)
    if (x / 2 >= h.back()) self_h.push_back(x), self_d.push_back(e(x) - e(x / 2));
  const OrderFit own = fit_order(self_h, self_d, 0.0, 0.1, kOrderWindowPoints, 0.0);
  const OrderFit matched = self_convergence_fit(self_h, self_d, reference, 0.1, 0.0);
  EXPECT_GT(own.h_max, reference.h_max * kWindowSlack);
  EXPECT_GE(matched.h_min, reference.h_min / kWindowSlack);
  EXPECT_LE(matched.h_max, reference.h_max * kWindowSlack);
  EXPECT_NEAR(matched.slope, 2.0, 1e-9);
  // over its own window the method reads another slope than the reference
  EXPECT_EQ(judge_order(reference, own, 2).reason, "self-convergence disagrees");
  EXPECT_EQ(judge_order(reference, matched, 2).verdict, "as declared");
  // a reference that reads another slope than the method's own distances
  // over the same steps is still refused: distances of order 3 there
  std::vector<double> cubic;
  for (double x : self_h) cubic.push_back(std::pow(x, 3));
  const OrderJudgement refused = judge_order(reference, self_convergence_fit(self_h, cubic, reference, 0.1, 0.0), 2);
  EXPECT_EQ(refused.verdict, "inconclusive");
  EXPECT_EQ(refused.reason, "self-convergence disagrees");
  // no distance inside the window: the distances' own window
  const std::vector<double> far_h{1.0, 0.5, 0.25, 0.125, 0.0625}, far_d{1e-2, 2.5e-3, 6e-4, 1.5e-4, 4e-5};
  EXPECT_DOUBLE_EQ(self_convergence_fit(far_h, far_d, reference, 0.1, 0.0).slope,
                   fit_order(far_h, far_d, 0.0, 0.1, kOrderWindowPoints, 0.0).slope);
}

TEST(OrderLadderRules, AWideIntervalWhoseSlopesStillMoveAsksForFinerSteps) {
  // rk4-projected's omega on chaplygin-valley: the local slope wanders
  // 3.3, 4.9, 5.6 over the smallest halvings, an interval of +-0.5
  const std::vector<double> h = ladder(10);
  const auto e = [](double x) { return std::pow(x, 4) * (1 + 0.6 * std::sin(3 * std::log(x))); };
  const OrderFit fit = fit_order(h, errors(h, e), 1e-16, 0.1, 8, 0.0);
  ASSERT_EQ(fit.at_floor, 0);
  ASSERT_EQ(inconclusive_reason(fit, 4), "wide interval");
  EXPECT_FALSE(fit.asymptotic);
  EXPECT_TRUE(wants_finer_steps(fit, 4));
  // the same errors, the smallest steps on the plateau: no finer step helps
  const OrderFit floored = fit_order(h, errors(h, e), 1e-10, 0.1, 8, 0.0);
  ASSERT_GT(floored.at_floor, 0);
  EXPECT_FALSE(wants_finer_steps(floored, 4));
  // an interval that is wide although the halvings agree: not asked
  OrderFit settled_but_wide = fit;
  settled_but_wide.asymptotic = true;
  EXPECT_FALSE(wants_finer_steps(settled_but_wide, 4));
}

// A fit whose halvings agree and whose window lies below the bar, with
// halving slopes s from the smallest step up.
OrderFit below_the_bar(double slope, std::vector<double> s, int at_floor = 0) {
  OrderFit fit;
  fit.points = 6;
  fit.asymptotic = slopes_agree(s);
  fit.slope = slope;
  fit.slope_ci95 = 0.1;
  fit.halving_slopes = std::move(s);
  fit.at_floor = at_floor;
  return fit;
}

TEST(OrderLadderRules, ASlopeStillClimbingTowardsItsOrderIsNotLower) {
  // rk4's omega on paraboloid-chaplygin: halvings 3.82, 3.60, 3.63 agree
  // within +-0.19 and the window reads 3.63 +- 0.10, but the smallest step's
  // slope is 3.82: no verdict, and a finer step decides
  const OrderFit rk4 = below_the_bar(3.63, {3.82, 3.60, 3.63});
  ASSERT_TRUE(rk4.asymptotic);
  EXPECT_TRUE(climbing_to(rk4, 3.8));
  EXPECT_EQ(order_verdict(rk4, 4), "inconclusive");
  EXPECT_EQ(inconclusive_reason(rk4, 4), "pre-asymptotic");
  EXPECT_TRUE(wants_finer_steps(rk4, 4));
  // rk4-projected's omega on chaplygin-bumpy-long: 3.78, one more halving at
  // its last rise (+0.27) passes 3.8
  EXPECT_EQ(order_verdict(below_the_bar(3.56, {3.78, 3.51, 3.72}), 4), "inconclusive");
  // against the plateau the same slopes say so, and no finer step helps
  const OrderFit floored = below_the_bar(3.63, {3.82, 3.60, 3.63}, 2);
  EXPECT_EQ(inconclusive_reason(floored, 4), "no asymptotic range above the plateau");
  EXPECT_FALSE(wants_finer_steps(floored, 4));
  // a method that lost its order stays lower: level (cf4 reversed, 2.0 for
  // 4), falling towards small steps (the perturbed RK4's 1.0), or rising
  // too little to reach the bar (cg3 reversed on chaplygin-bowl, 1.93 for 3)
  EXPECT_EQ(order_verdict(below_the_bar(2.0, {2.0, 2.0, 2.0}), 4), "lower");
  EXPECT_EQ(order_verdict(below_the_bar(1.05, {1.0, 1.1, 1.2}), 4), "lower");
  EXPECT_EQ(order_verdict(below_the_bar(1.81, {1.93, 1.85, 1.71}), 3), "lower");
  // a slope level just under the bar is lower: 3.6 at every halving
  EXPECT_EQ(order_verdict(below_the_bar(3.6, {3.6, 3.6, 3.6}), 4), "lower");
}

TEST(OrderLadderRules, RunsThatFailedAskForFinerStepsWhereASmallerStepMayRun) {
  // euler on chaplygin-valley: every run of the ladder down to 2^-10 leaves
  // the chart or the domain
  std::vector<FitRun> runs;
  const auto e = [](double x) { return x; };
  for (double h : ladder(10)) runs.push_back(run_erring(h, e, 1e-13, 1, false));
  const auto failed = group_orders(pointers(runs), OrderScale{1e-13, 1.0});
  for (const ComponentOrder& o : failed) EXPECT_EQ(o.judgement.reason, "failed runs");
  EXPECT_FALSE(wants_finer_steps(failed));  // the fit alone does not ask
  for (Status s : {Status::domain, Status::lift_off, Status::chart_limit, Status::diverged, Status::curvature})
    EXPECT_TRUE(failed_runs_want_finer_steps(failed, s)) << status_name(s);
  // a crash, a time-out, a library error, the budget or R off SO(3) is no matter of the step
  for (Status s : {Status::crashed, Status::timeout, Status::error, Status::max_steps, Status::off_group})
    EXPECT_FALSE(failed_runs_want_finer_steps(failed, s)) << status_name(s);
  // the smallest step ran (two errors, under the ceiling) but the rest failed: finer steps add points
  runs.back() = run_erring(runs.back().h, e, 1e-13, 1);
  runs[runs.size() - 2] = run_erring(runs[runs.size() - 2].h, e, 1e-13, 1);
  const auto two = group_orders(pointers(runs), OrderScale{1e-13, 1.0});
  EXPECT_EQ(two[0].judgement.reason, "failed runs");
  EXPECT_TRUE(failed_runs_want_finer_steps(two, Status::ok));
  // the same two on the plateau: no finer step can add a point
  const auto floored = group_orders(pointers(runs), OrderScale{1e-2, 1.0});
  EXPECT_FALSE(failed_runs_want_finer_steps(floored, Status::ok));
}

}  // namespace
}  // namespace rb

// Order verdicts that hold both ways (docs/usage.md, "Observed orders"): a
// method that loses its order at small steps far above the plateau is not
// certified; a rounding plateau is left out only at the rounding level;
// smallest steps whose halving slopes still move decide nothing and ask for
// a finer ladder, and so does a ladder that ends above the ceiling; a
// component on the plateau at every step is exact; self-convergence
// confirms the reference's slope.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "bench/lib/fit_run.hpp"
#include "bench/lib/group_orders.hpp"
#include "bench/lib/order_fit.hpp"
#include "bench/lib/self_convergence.hpp"
#include "tests/bench/error_series.hpp"

namespace rb {
namespace {

TEST(OrderVerdictsBothWays, AnOrderLostAtSmallStepsFarAboveTheFloorIsNotCertified) {
  // the perturbed RK4: 1e-2 h^4 + 2.5e-6 h, of slope 1 below h ~ 0.03
  // at errors near 1e-8, four decades above the floor (1e-13)
  const std::vector<double> h = ladder(14);
  const auto e = errors(h, [](double x) { return 1e-2 * std::pow(x, 4) + 2.5e-6 * x; });
  const OrderFit fit = fit_order(h, e, 1e-13, 0.1, 8);
  EXPECT_NEAR(fit.slope, 1.0, 0.05);
  EXPECT_EQ(fit.at_floor, 0);
  EXPECT_TRUE(fit.asymptotic);
  EXPECT_EQ(order_verdict(fit, 4), "lower");
}

TEST(OrderVerdictsBothWays, AMethodThatDoesNotConvergeIsNeverAsDeclared) {
  // sum b = 1 + 9e-7: a plateau at 1.5e-5, far above floor and rounding
  const std::vector<double> h = ladder(12);
  const auto e = errors(h, [](double x) { return 1e-2 * std::pow(x, 4) + 1.5e-5; });
  const OrderFit fit = fit_order(h, e, 1e-13, 0.1, 8);
  EXPECT_LT(fit.slope, 0.5);
  EXPECT_NE(order_verdict(fit, 4), "as declared");
}

TEST(OrderVerdictsBothWays, ARoundingRiseIsLeftOutAtItsMeasuredLevel) {
  // order 5 down to a rounding rise as the reference measured it: its own
  // error (the floor, 1e-15) at its finer solution's step 2^-11, growing
  // with the steps below it (plateau_level); within 100 x that level the
  // points are left out, and the slope above them is the method's
  const std::vector<double> h = ladder(18);
  const double floor = 1e-15, step = std::ldexp(1.0, -11);
  EXPECT_DOUBLE_EQ(plateau_level(floor, step, std::ldexp(1.0, -10)), floor);
  EXPECT_DOUBLE_EQ(plateau_level(floor, step, std::ldexp(1.0, -14)), 8 * floor);
  // the run's own rounding at 3 x the reference's level
  const auto e = errors(h, [&](double x) { return 1e-1 * std::pow(x, 5) + 3 * plateau_level(floor, step, x); });
  const OrderFit fit = fit_order(h, e, floor, 0.1, 8, step);
  EXPECT_GT(fit.at_floor, 0);
  EXPECT_NEAR(fit.slope, 5.0, 0.1);
  EXPECT_EQ(order_verdict(fit, 5), "as declared");
  // told no step, the floor alone marks the plateau: the rise is fitted,
  // and no verdict certifies order 5
  EXPECT_NE(order_verdict(fit_order(h, e, floor, 0.1, 8, 0.0), 5), "as declared");
}

TEST(OrderVerdictsBothWays, APointFarAboveTheMeasuredPlateauIsFitted) {
  // the RK4 with a42 = 1e-3 on valley-sideways (t_end 5 s) errs
  // 1.3e-12 at 2^-10, where an assumed rounding level of 10 eps t_end / h
  // (1.1e-11) left it out; measured from a reference of own error 1e-15,
  // the point is 1300 x above the plateau, and it is fitted
  const std::vector<double> h = ladder(10);
  const auto e = errors(h, [](double x) { return 1.3e-12 * std::pow(x / std::ldexp(1.0, -10), 4); });
  const OrderFit fit = fit_order(h, e, 1e-15, 0.1, 8, std::ldexp(1.0, -11));
  EXPECT_EQ(fit.at_floor, 0);
  EXPECT_DOUBLE_EQ(fit.h_min, std::ldexp(1.0, -10));
}

// truly order 3, declared 4: h^4 + 7.27e-4 h^3, whose halving slopes
// fall 3.94, 3.88, 3.79 down to 2^-9 (the RK4 with a42 = 1e-3 on
// valley-sideways) and 3.64, 3.48, ... below
double falls_to_three(double x) { return std::pow(x, 4) + 7.27e-4 * std::pow(x, 3); }

TEST(OrderVerdictsBothWays, ASlopeThatFallsTowardsSmallStepsIsNeverAPass) {
  const std::vector<double> h = ladder(9);
  const OrderFit fit = fit_order(h, errors(h, falls_to_three), 1e-18, 0.1, 8);
  ASSERT_GE(fit.trend_slopes.size(), 3u);
  EXPECT_NEAR(fit.trend_slopes[0], 3.79, 0.01);
  EXPECT_NEAR(fit.trend_slopes[1], 3.88, 0.01);
  EXPECT_NEAR(fit.trend_slopes[2], 3.94, 0.01);
  // what the old rule passed: halvings that agree within +-0.15, a window above 3.8
  EXPECT_TRUE(fit.asymptotic);
  EXPECT_GE(fit.slope - fit.slope_ci95, 3.8);
  // the trend: falling, its whole interval below 0
  EXPECT_LT(fit.trend + fit.trend_ci95, 0.0);
  EXPECT_TRUE(falling(fit, 4));
  EXPECT_EQ(order_verdict(fit, 4), "inconclusive");
  EXPECT_EQ(inconclusive_reason(fit, 4), "pre-asymptotic");
  EXPECT_TRUE(wants_finer_steps(fit, 4));
  // four halvings more: the slope keeps falling, and the verdict is lower, never as declared
  const std::vector<double> longer = ladder(13);
  EXPECT_EQ(order_verdict(fit_order(longer, errors(longer, falls_to_three), 1e-18, 0.1, 8), 4), "lower");
}

TEST(OrderVerdictsBothWays, TheTrendOfMadeUpSlopes) {
  // the slopes, smallest step first: falling, interval below 0
  const LineFit fall = trend_of({3.79, 3.88, 3.94, 3.99, 4.02});
  EXPECT_LT(fall.slope, 0.0);
  EXPECT_LT(fall.slope + fall.slope_ci95, 0.0);
  OrderFit fit;
  fit.trend_slopes = {3.79, 3.88, 3.94, 3.99, 4.02};
  fit.trend = fall.slope, fit.trend_ci95 = fall.slope_ci95;
  EXPECT_TRUE(falling(fit, 4));
  // settling onto 4 from above, each fall half the one before: no fall
  const std::vector<double> settling{4.02, 4.06, 4.14, 4.3, 4.62};
  const LineFit settle = trend_of(settling);
  EXPECT_LT(settle.slope + settle.slope_ci95, 0.0);  // significant, but towards the order
  fit.trend_slopes = settling;
  fit.trend = settle.slope, fit.trend_ci95 = settle.slope_ci95;
  EXPECT_FALSE(falling(fit, 4));
  // the same falls, 0.05 lower: past the declared order, falling
  const std::vector<double> past{3.97, 4.01, 4.09, 4.25, 4.57};
  const LineFit beyond = trend_of(past);
  fit.trend_slopes = past;
  fit.trend = beyond.slope, fit.trend_ci95 = beyond.slope_ci95;
  EXPECT_TRUE(falling(fit, 4));
  // a fall of a thousandth a halving is no fall (rk3 on bowl-3d: 3.000 at every halving)
  const std::vector<double> level{3.996, 3.997, 3.998, 3.999, 4.0};
  const LineFit flat = trend_of(level);
  fit.trend_slopes = level;
  fit.trend = flat.slope, fit.trend_ci95 = flat.slope_ci95;
  EXPECT_FALSE(falling(fit, 4));
  // scattered slopes: no trend their interval can tell from 0
  const LineFit scatter = trend_of({4.1, 3.9, 4.05, 3.95, 4.0});
  EXPECT_GE(scatter.slope + scatter.slope_ci95, 0.0);
  EXPECT_LE(scatter.slope - scatter.slope_ci95, 0.0);
  // two slopes have no interval
  EXPECT_TRUE(std::isnan(trend_of({3.9, 4.0}).slope));
}

// order 4 below a sixth-order term that leads at large steps: the halving
// slopes fall from 6 towards 4 (4.9, 4.3, 4.1 at h = 2^-4 .. 2^-6)
double order_four_below_six(double x) { return 1e-3 * std::pow(x, 4) + 1e-1 * std::pow(x, 6); }

TEST(OrderVerdictsBothWays, MovingHalvingSlopesArePreAsymptoticAndAskForFinerSteps) {
  std::vector<double> h;
  for (int k = 0; k <= 24; ++k) h.push_back(std::exp2(-k / 4.0));
  const OrderFit coarse = fit_order(h, errors(h, order_four_below_six), 1e-16, 0.1, 8);
  ASSERT_EQ(coarse.halving_slopes.size(), 3u);
  EXPECT_FALSE(coarse.asymptotic);
  EXPECT_TRUE(pre_asymptotic(coarse));
  EXPECT_EQ(order_verdict(coarse, 4), "inconclusive");
  EXPECT_EQ(inconclusive_reason(coarse, 4), "pre-asymptotic");
  EXPECT_TRUE(wants_finer_steps(coarse, 4));
  // six more halvings: the slopes settle near 4 and decide
  for (int k = 7; k <= 12; ++k) h.push_back(std::ldexp(1.0, -k));
  const OrderFit fine = fit_order(h, errors(h, order_four_below_six), 1e-16, 0.1, 8);
  ASSERT_EQ(fine.halving_slopes.size(), 3u);
  EXPECT_TRUE(fine.asymptotic);
  EXPECT_NEAR(fine.slope, 4.0, 0.1);  // the window reaches up to 0.15 off its slope
  EXPECT_EQ(order_verdict(fine, 4), "as declared");
  EXPECT_FALSE(wants_finer_steps(fine, 4));
}

TEST(OrderVerdictsBothWays, MovingSlopesThatMeetThePlateauHaveNoVerdict) {
  // the same errors, but a floor at 1e-12 ends the ladder before the
  // slopes settle: no verdict, and no finer step can help
  std::vector<double> h;
  for (int k = 0; k <= 40; ++k) h.push_back(std::exp2(-k / 4.0));
  const OrderFit fit = fit_order(h, errors(h, order_four_below_six), 1e-12, 0.1, 8);
  EXPECT_GT(fit.at_floor, 0);
  EXPECT_EQ(order_verdict(fit, 4), "inconclusive");
  EXPECT_EQ(inconclusive_reason(fit, 4), "no asymptotic range above the plateau");
  EXPECT_FALSE(wants_finer_steps(fit, 4));
}

// A ladder cut short by the plateau (floor 1e-9, so errors under 1e-7 are
// left out) holds two halvings of an order-8 method between the ceiling and
// the plateau: 10 h^8 there reads 8.0 and 8.0, which bound the order from
// below; no finer step can add a third halving.
TEST(OrderVerdictsBothWays, TwoHalvingsThePlateauEndsCertifyButNeverCondemn) {
  const std::vector<double> h = ladder(12);
  const OrderFit pure = fit_order(h, errors(h, [](double x) { return 10 * std::pow(x, 8); }), 1e-9, 0.1, 8);
  ASSERT_EQ(pure.halving_slopes.size(), 2u);
  EXPECT_GT(pure.at_floor, 0);
  EXPECT_FALSE(pure.asymptotic);
  EXPECT_TRUE(certified_at_plateau(pure, 7.8));
  EXPECT_EQ(order_verdict(pure, 8), "as declared");
  // the same series declared 9: two slopes at 8 bound nothing above 8.8, and a
  // ladder the plateau cut short never condemns
  EXPECT_EQ(order_verdict(pure, 9), "inconclusive");
  EXPECT_EQ(inconclusive_reason(pure, 9), "no asymptotic range above the plateau");
  // an error that flattens into the plateau (9e-8 added, under the plateau's
  // 1e-7 at small steps): the slope falls to 6.2 next to it; no verdict
  // either way, although 6.2 is far below 8
  const OrderFit flattening =
      fit_order(h, errors(h, [](double x) { return 10 * std::pow(x, 8) + 9e-8; }), 1e-9, 0.1, 8);
  ASSERT_EQ(flattening.halving_slopes.size(), 2u);
  EXPECT_LT(flattening.halving_slopes[0], 7.0);
  EXPECT_EQ(order_verdict(flattening, 8), "inconclusive");
  // an order lost towards small steps (3e-6 h added): the slopes fall from
  // 7.8 to 1.1; never as declared
  const OrderFit lost = fit_order(h, errors(h, [](double x) { return 10 * std::pow(x, 8) + 3e-6 * x; }), 1e-9, 0.1, 8);
  EXPECT_NE(order_verdict(lost, 8), "as declared");
  EXPECT_FALSE(certified_at_plateau(lost, 7.8));
}

// An order-8 method whose slope climbs towards 8 as h falls (h^8 / (1 +
// 30 h^3)), cut by a plateau at 1e-9 (floor 1e-11) below h = 0.088: its
// halvings read 7.81 and 7.00, which certify nothing, but the quarter-step
// ladder's half-octave rungs read 7.89, 7.72, 7.33 from the smallest step
// up: climbing towards small steps, the smallest above the bar.
double climbing_to_eight(double x) { return std::pow(x, 8) / (1.0 + 30.0 * std::pow(x, 3)); }

TEST(OrderVerdictsBothWays, RungsThatClimbToThePlateauCertifyButNeverCondemn) {
  const std::vector<double> h = ladder(12);
  const OrderFit fit = fit_order(h, errors(h, climbing_to_eight), 1e-11, 0.1, 8);
  EXPECT_GT(fit.at_floor, 0);
  EXPECT_FALSE(fit.asymptotic);
  ASSERT_EQ(fit.halving_slopes.size(), 3u);
  EXPECT_LT(fit.halving_slopes[1], 7.8);  // the halvings alone certify nothing
  ASSERT_EQ(fit.rung_slopes.size(), 3u);
  EXPECT_GE(fit.rung_slopes[0], 7.8);
  EXPECT_LT(fit.rung_slopes[2], fit.rung_slopes[0]);  // climbing towards small steps
  EXPECT_TRUE(certified_at_plateau(fit, 7.8));
  EXPECT_EQ(order_verdict(fit, 8), "as declared");
  // declared 9: the rungs bound nothing above 7.9, and they never condemn
  EXPECT_EQ(order_verdict(fit, 9), "inconclusive");
  EXPECT_EQ(inconclusive_reason(fit, 9), "no asymptotic range above the plateau");
  // an order lost towards small steps just above the plateau (2e-8 h
  // added): the smallest rung falls under the bar; never as declared
  const OrderFit lost =
      fit_order(h, errors(h, [](double x) { return climbing_to_eight(x) + 2e-8 * x; }), 1e-11, 0.1, 8);
  ASSERT_GE(lost.rung_slopes.size(), 2u);
  EXPECT_LT(lost.rung_slopes[0], 7.8);
  EXPECT_FALSE(certified_at_plateau(lost, 7.8));
  EXPECT_NE(order_verdict(lost, 8), "as declared");
  // rungs that fall towards small steps by more than the agreement (8.97,
  // 8.64, 8.38 down to the plateau for h^8 + 30 h^10) certify nothing, though
  // all lie above the bar: the slope may fall further below the plateau
  const OrderFit falling =
      fit_order(h, errors(h, [](double x) { return std::pow(x, 8) + 30.0 * std::pow(x, 10); }), 1e-11, 0.1, 8);
  ASSERT_GE(falling.rung_slopes.size(), 2u);
  EXPECT_GT(*std::max_element(falling.rung_slopes.begin() + 1, falling.rung_slopes.end()),
            falling.rung_slopes[0] + 0.4);
  EXPECT_FALSE(certified_at_plateau(falling, 7.8));
}

// A settled fit whose interval, [3.65, 3.85], straddles declared 4 - 0.2.
OrderFit straddling(int at_floor, std::vector<double> rungs) {
  OrderFit fit;
  fit.points = 5;
  fit.asymptotic = true;
  fit.slope = 3.75;
  fit.slope_ci95 = 0.1;
  fit.at_floor = at_floor;
  fit.halving_slopes = {rungs.front()};
  fit.rung_slopes = std::move(rungs);
  return fit;
}

TEST(OrderVerdictsBothWays, AStraddlingIntervalIsDecidedOnlyByThePlateau) {
  // cf4's omega on chaplygin-valley: 3.92, 3.83, 3.60 from the smallest
  // step up, the next step on the plateau: certified
  EXPECT_EQ(order_verdict(straddling(1, {3.92, 3.83, 3.60}), 4), "as declared");
  // the same slopes with nothing on the plateau: a finer step decides
  const OrderFit open = straddling(0, {3.92, 3.83, 3.60});
  EXPECT_EQ(order_verdict(open, 4), "inconclusive");
  EXPECT_EQ(inconclusive_reason(open, 4), "straddles");
  EXPECT_TRUE(wants_finer_steps(open, 4));
  // the smallest rung under the bar (slopes falling towards small steps):
  // still straddles, and never lower
  const OrderFit falling = straddling(1, {3.60, 3.83, 3.92});
  EXPECT_EQ(order_verdict(falling, 4), "inconclusive");
  EXPECT_EQ(inconclusive_reason(falling, 4), "straddles");
}

TEST(OrderVerdictsBothWays, OmegasCeilingScalesWithTheLargestOmega) {
  // euler's omega on bowl-3d: |omega| up to 13 rad/s, error 700 h rad/s; at
  // 0.1 rad/s only the steps from 2^-13 down stay under the ceiling
  std::size_t omega = 0, contact = 0;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    if (std::string(kErrorComponents[i].name) == "omega") omega = i;
    if (std::string(kErrorComponents[i].name) == "contact") contact = i;
  }
  EXPECT_DOUBLE_EQ(order_ceiling(omega, 13.0), 1.3);
  EXPECT_DOUBLE_EQ(order_ceiling(contact, 13.0), 0.1);  // lengths and angles keep 0.1
  const std::vector<double> h = ladder(15);
  const auto e = errors(h, [](double x) { return 700.0 * x; });
  const OrderFit absolute = fit_order(h, e, 1e-13, 0.1, 8);
  EXPECT_EQ(absolute.points, 3);
  EXPECT_EQ(inconclusive_reason(absolute, 1), "too few points");
  const OrderFit scaled = fit_order(h, e, 1e-13, order_ceiling(omega, 13.0), 8);
  EXPECT_GE(scaled.points, 4);
  EXPECT_EQ(order_verdict(scaled, 1), "as declared");
  // the wider window condemns as readily: order 1 declared 2 is lower
  EXPECT_EQ(order_verdict(scaled, 2), "lower");
}

OrderFit no_fit() {
  OrderFit fit;
  fit.slope = NAN;
  return fit;
}

OrderFit settled(double slope) {
  OrderFit fit;
  fit.points = 6;
  fit.asymptotic = true;
  fit.slope = slope;
  fit.slope_ci95 = 0.05;
  return fit;
}

TEST(OrderVerdictsBothWays, AComponentOnThePlateauAtEveryStepIsExact) {
  // an error of 0.5 x the floor at every step: exact (RK3's centre on a
  // path quadratic in t)
  const std::vector<double> h = ladder(10);
  const auto flat = errors(h, [](double) { return 5e-14; });
  const OrderFit fit = fit_order(h, flat, 1e-13, 0.1, 8);
  EXPECT_TRUE(fit.all_at_plateau);
  EXPECT_EQ(order_verdict(fit, 3), "exact");
  EXPECT_EQ(judge_order(fit, no_fit(), 3).verdict, "exact");
  // one step above the plateau (the largest, at 100 x the floor's multiple): not exact
  auto one_above = flat;
  one_above[0] = 1e-9;
  const OrderFit risen = fit_order(h, one_above, 1e-13, 0.1, 8);
  EXPECT_FALSE(risen.all_at_plateau);
  EXPECT_EQ(order_verdict(risen, 3), "inconclusive");
  EXPECT_EQ(inconclusive_reason(risen, 3), "floor");
  // failed runs (no error: large steps that left the chart) neither make nor
  // break it, and they are failures of their own
  auto failed = flat;
  for (int i = 0; i < 7; ++i) failed[static_cast<std::size_t>(i)] = NAN;
  EXPECT_EQ(order_verdict(fit_order(h, failed, 1e-13, 0.1, 8), 3), "exact");
  // with one finite error above the plateau among them: not exact
  failed[7] = 1e-9;
  EXPECT_NE(order_verdict(fit_order(h, failed, 1e-13, 0.1, 8), 3), "exact");
  // three steps are too few to call anything exact, and so are three errors
  const std::vector<double> three(h.begin(), h.begin() + 3);
  EXPECT_NE(order_verdict(fit_order(three, errors(three, [](double) { return 5e-14; }), 1e-13, 0.1, 8), 3), "exact");
  std::vector<double> three_left(h.size(), NAN);
  for (std::size_t i = 0; i < 3; ++i) three_left[i] = 5e-14;
  EXPECT_NE(order_verdict(fit_order(h, three_left, 1e-13, 0.1, 8), 3), "exact");
}

TEST(OrderVerdictsBothWays, ALadderEndingAboveTheCeilingAsksForFinerSteps) {
  // order 1 with a large constant: under the ceiling 0.1 only at the two
  // smallest steps, nothing on the plateau: a finer step could decide
  const std::vector<double> h = ladder(10);
  const auto e = errors(h, [](double x) { return 40.0 * x; });
  const OrderFit fit = fit_order(h, e, 1e-13, 0.1, 8);
  EXPECT_EQ(fit.points, 2);
  EXPECT_EQ(inconclusive_reason(fit, 1), "too few points");
  EXPECT_TRUE(wants_finer_steps(fit, 1));
  // the same few points, but the smallest step on the plateau: no finer step helps
  auto floored = e;
  floored.back() = 1e-12;
  EXPECT_FALSE(wants_finer_steps(fit_order(h, floored, 1e-13, 0.1, 8), 1));
  // runs that failed (no error) above the two: a failing method gets no more runs
  auto failed = e;
  for (std::size_t i = 0; i + 2 < failed.size(); ++i) failed[i] = NAN;
  EXPECT_FALSE(wants_finer_steps(fit_order(h, failed, 1e-13, 0.1, 8), 1));
  // a ladder of three runs, as a user chose it, stays as it is
  const std::vector<double> three(h.end() - 3, h.end());
  EXPECT_FALSE(wants_finer_steps(fit_order(three, errors(three, [](double x) { return 40.0 * x; }), 1e-13, 0.1, 8), 1));
}

TEST(OrderVerdictsBothWays, TooFewPointsBecauseRunsFailedSaySo) {
  // euler on chaplygin-valley: every run of the ladder leaves the chart
  const std::vector<double> h = ladder(10);
  const std::vector<double> none(h.size(), NAN);
  const OrderFit all_failed = fit_order(h, none, 1e-13, 0.1, 8);
  EXPECT_EQ(all_failed.failed, static_cast<int>(h.size()));
  EXPECT_EQ(order_verdict(all_failed, 1), "inconclusive");
  EXPECT_EQ(inconclusive_reason(all_failed, 1), "failed runs");
  EXPECT_FALSE(wants_finer_steps(all_failed, 1));
  // three errors at the smallest steps, the larger steps failed
  auto three = none;
  for (std::size_t i = h.size() - 3; i < h.size(); ++i) three[i] = 1e-3 * h[i];
  EXPECT_EQ(inconclusive_reason(fit_order(h, three, 1e-13, 0.1, 8), 1), "failed runs");
  // with two errors above the ceiling among them, the ladder ends before its
  // errors come under the ceiling: too few points, and finer steps decide
  three[h.size() - 4] = 0.5, three[h.size() - 5] = 0.6;
  const OrderFit short_ladder = fit_order(h, three, 1e-13, 0.1, 8);
  EXPECT_EQ(inconclusive_reason(short_ladder, 1), "too few points");
  EXPECT_TRUE(wants_finer_steps(short_ladder, 1));
}

TEST(OrderVerdictsBothWays, SelfConvergenceConfirmsTheReferenceSlopeOrWithholdsTheVerdict) {
  EXPECT_EQ(judge_order(settled(4.0), settled(4.1), 4).verdict, "as declared");
  EXPECT_EQ(judge_order(settled(1.0), settled(1.05), 4).verdict, "lower");
  // a reference that reads 4 where the method's own halvings read 3: no verdict
  const OrderJudgement disagree = judge_order(settled(4.0), settled(3.0), 4);
  EXPECT_EQ(disagree.verdict, "inconclusive");
  EXPECT_EQ(disagree.reason, "self-convergence disagrees");
  const OrderJudgement none = judge_order(settled(4.0), no_fit(), 4);
  EXPECT_EQ(none.verdict, "inconclusive");
  EXPECT_EQ(none.reason, "no self-convergence");
  // the reference fit's own reason comes first
  EXPECT_EQ(judge_order(no_fit(), settled(4.0), 4).reason, "too few points");
}

FitRun run_at(double h, double x, bool ok = true) {
  FitRun r;
  r.h = h;
  r.ok = ok;
  r.stop_time = 2.0;
  r.end.alpha = Vec2(x, 0.0);
  r.end.centre = Vec3(x, 0.0, 0.1);
  r.end.omega = Vec3::Zero();
  r.end.R = Mat3::Identity();
  return r;
}

TEST(SelfConvergence, PairsEachRunWithItsHalfStepOnly) {
  // ends x(h) = 1 + h^2: D(h) = h^2 - h^2 / 4
  const FitRun a = run_at(0.5, 1.25), b = run_at(0.25, 1.0625), c = run_at(0.125, 1.015625);
  const FitRun odd = run_at(0.3, 1.09);              // no partner at 0.15
  const FitRun failed = run_at(0.0625, 7.0, false);  // stopped: no pair with c
  const std::vector<SelfDifference> d = self_differences({&odd, &a, &c, &b, &failed});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d[0].h, 0.25);
  EXPECT_DOUBLE_EQ(d[0].distance[0], 0.0625 - 0.015625);
  EXPECT_DOUBLE_EQ(d[1].h, 0.5);
  EXPECT_DOUBLE_EQ(d[1].distance[0], 0.25 - 0.0625);
  EXPECT_DOUBLE_EQ(d[1].distance[3], 0.0);  // the same rotation
}

}  // namespace
}  // namespace rb

// The observed-order fit on data with a known answer: the slope, the floor,
// the ceiling and the pre-asymptotic range.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/lib/order_fit.hpp"
#include "tests/bench/error_series.hpp"

namespace rb {
namespace {

std::vector<double> steps(int from, int to) {
  std::vector<double> h;
  for (int k = from; k <= to; ++k) h.push_back(std::ldexp(1.0, -k));
  return h;
}

TEST(OrderFit, ExactPowerLawGivesItsExponent) {
  const std::vector<double> h = steps(2, 9);
  const OrderFit fit = fit_order(h, errors(h, [](double x) { return 3.0 * std::pow(x, 4); }));
  EXPECT_NEAR(fit.slope, 4.0, 1e-12);
  EXPECT_NEAR(fit.intercept, std::log10(3.0), 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
  EXPECT_NEAR(fit.residual, 0.0, 1e-12);
  EXPECT_EQ(fit.points, 6);  // the six smallest steps
  EXPECT_DOUBLE_EQ(fit.h_min, std::ldexp(1.0, -9));
}

TEST(OrderFit, PointsOnTheFloorAreLeftOut) {
  // rounding flattens the curve below 1e-12; the points there are left out
  // by the floor, and the fit is the method's slope
  const std::vector<double> h = steps(1, 14);
  const std::vector<double> e = errors(h, [](double x) { return 1e-2 * std::pow(x, 5) + 1e-12; });
  const OrderFit fit = fit_order(h, e, 1e-12);
  EXPECT_NEAR(fit.slope, 5.0, 0.05);
  EXPECT_GT(fit.h_min, std::ldexp(1.0, -6));  // 1e-2 h^5 > 1e-11 only above h ~ 0.02
  // fitting the plateau as if it were data would read a much lower order
  EXPECT_LT(fit_order(std::vector<double>(h.end() - 5, h.end()), std::vector<double>(e.end() - 5, e.end())).slope, 1.0);
}

TEST(OrderFit, PreAsymptoticStepsAndTheCeilingAreLeftOut) {
  // e = h^2 (1 + 3 h): third-order contamination at large h; and errors
  // above the ceiling (0.1) with a lucky small one beyond them
  std::vector<double> h = steps(0, 10);
  std::vector<double> e = errors(h, [](double x) { return x * x * (1.0 + 3.0 * x); });
  h.push_back(2.0);
  e.push_back(1e-4);  // lucky: below the ceiling but past points above it
  const OrderFit fit = fit_order(h, e);
  EXPECT_NEAR(fit.slope, 2.0, 0.1);
  EXPECT_LT(fit.h_max, 0.1);
  EXPECT_GT(fit.slope_ci95, 0.0);
}

TEST(OrderFit, TooFewPointsGiveNoSlope) {
  EXPECT_TRUE(std::isnan(fit_order({0.1}, {1e-3}).slope));
  EXPECT_TRUE(std::isnan(fit_order({0.1, 0.05}, {NAN, 1e-3}).slope));
  EXPECT_EQ(fit_order({0.1, 0.05}, {1e-3, 2.5e-4}).points, 2);
}

TEST(OrderFit, PreAsymptoticStepsOfAnEighthOrderMethodDoNotDecide) {
  // e = h^8 / (1 + 30 h^3): order 8 only below h ~ 0.1, much flatter above
  // (as rkmk8's and odeint-fehlberg78's rotation errors are); the window of
  // the smallest steps reads 8, not the slope of the large ones
  const std::vector<double> h = steps(0, 7);
  const OrderFit fit = fit_order(h, errors(h, [](double x) { return std::pow(x, 8) / (1.0 + 30.0 * x * x * x); }));
  EXPECT_NEAR(fit.slope, 8.0, 0.1);
  EXPECT_LE(fit.h_max, 0.125);
  EXPECT_EQ(order_verdict(fit, 8), "as declared");
  // all points in one line read 7.4 and would fail the method
  EXPECT_LT(fit_line(errors(h, [](double x) { return std::log10(x); }),
                     errors(h, [](double x) { return std::log10(std::pow(x, 8) / (1.0 + 30.0 * x * x * x)); }))
                .slope,
            7.6);
}

TEST(OrderVerdict, ThreePointsAreInconclusiveHoweverGoodTheirSlope) {
  const std::vector<double> h = steps(4, 6);
  const OrderFit fit = fit_order(h, errors(h, [](double x) { return std::pow(x, 4); }));
  EXPECT_EQ(fit.points, 3);
  EXPECT_NEAR(fit.slope, 4.0, 1e-12);
  EXPECT_EQ(order_verdict(fit, 4), "inconclusive");
}

TEST(OrderVerdict, FollowsTheIntervalNotTheSlope) {
  OrderFit fit;
  fit.points = 6;
  fit.asymptotic = true;  // its halving slopes agree: only the interval decides
  fit.slope = 4.0;
  fit.slope_ci95 = 0.5;  // +-0.5: wider than +-0.3
  EXPECT_EQ(order_verdict(fit, 4), "inconclusive");
  fit.slope_ci95 = 0.1;
  EXPECT_EQ(order_verdict(fit, 4), "as declared");
  fit.slope = 5.2;  // higher than declared is no failure
  EXPECT_EQ(order_verdict(fit, 4), "as declared");
  fit.slope = 3.5;  // [3.4, 3.6] lies below 3.8
  EXPECT_EQ(order_verdict(fit, 4), "lower");
  fit.slope = 3.75;  // [3.65, 3.85] straddles 3.8
  EXPECT_EQ(order_verdict(fit, 4), "inconclusive");
  fit.slope = 3.95;  // [3.85, 4.05]: within 0.2
  EXPECT_EQ(order_verdict(fit, 4), "as declared");
}

TEST(OrderVerdict, NoisyDataGiveAWideIntervalAndNoVerdict) {
  // order 4 with a factor of 3 scattered on alternate points
  const std::vector<double> h = steps(2, 9);
  std::vector<double> e = errors(h, [](double x) { return std::pow(x, 4); });
  for (std::size_t i = 0; i < e.size(); i += 2) e[i] *= 3.0;
  const OrderFit fit = fit_order(h, e);
  EXPECT_GT(fit.slope_ci95, 0.3);
  EXPECT_EQ(order_verdict(fit, 4), "inconclusive");
}

TEST(OrderVerdict, AnInconclusiveVerdictSaysWhy) {
  // order 8 from h = 2^-2: above 10 x floor (1e-12) at only three steps, the
  // five others at the floor: "floor"
  std::vector<double> h = steps(2, 9);
  std::vector<double> e = errors(h, [](double x) { return std::max(1e-12, std::pow(x, 8)); });
  OrderFit fit = fit_order(h, e, 1e-12);
  EXPECT_EQ(fit.points, 3);
  EXPECT_EQ(fit.at_floor, 5);
  EXPECT_EQ(inconclusive_reason(fit, 8), "floor");
  // three points and nothing at the floor: "too few points"
  h = steps(1, 3);
  fit = fit_order(h, errors(h, [](double x) { return std::pow(x, 8); }), 1e-12);
  EXPECT_EQ(inconclusive_reason(fit, 8), "too few points");
  // scattered: "wide interval"
  h = steps(2, 9);
  e = errors(h, [](double x) { return std::pow(x, 4); });
  for (std::size_t i = 0; i < e.size(); i += 2) e[i] *= 3.0;
  EXPECT_EQ(inconclusive_reason(fit_order(h, e), 4), "wide interval");
  // a narrow interval across declared - 0.2: "straddles"; a verdict: no reason
  OrderFit narrow;
  narrow.points = 6;
  narrow.asymptotic = true;
  narrow.slope = 3.8;
  narrow.slope_ci95 = 0.1;
  EXPECT_EQ(inconclusive_reason(narrow, 4), "straddles");
  narrow.slope = 4.0;
  EXPECT_EQ(inconclusive_reason(narrow, 4), "");
}

TEST(LineFit, SlopeInterceptAndResidualOfKnownLines) {
  const LineFit exact = fit_line({-3, -5, -7, -9}, {-2.5, -4.5, -6.5, -8.5});
  EXPECT_NEAR(exact.slope, 1.0, 1e-14);
  EXPECT_NEAR(exact.intercept, 0.5, 1e-14);
  EXPECT_NEAR(exact.residual, 0.0, 1e-14);
  EXPECT_EQ(exact.points, 4);
  // residuals +-0.1 alternating about slope 0.5: rms 0.1
  const LineFit noisy = fit_line({0, 1, 2, 3}, {0.1, 0.4, 1.1, 1.4});
  EXPECT_NEAR(noisy.slope, 0.46, 1e-12);
  EXPECT_GT(noisy.residual, 0.05);
  EXPECT_TRUE(std::isnan(fit_line({1, 1}, {2, 3}).slope));
  EXPECT_EQ(fit_line({1, NAN, 2}, {1, 2, 3}).points, 2);
}

}  // namespace
}  // namespace rb

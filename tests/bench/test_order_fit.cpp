// The observed-order fit on data with a known answer: the slope, the floor,
// the ceiling and the pre-asymptotic range.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/lib/order_fit.hpp"

namespace rb {
namespace {

std::vector<double> steps(int from, int to) {
  std::vector<double> h;
  for (int k = from; k <= to; ++k) h.push_back(std::ldexp(1.0, -k));
  return h;
}

template <class F>
std::vector<double> errors(const std::vector<double>& h, F&& f) {
  std::vector<double> e;
  for (double x : h) e.push_back(f(x));
  return e;
}

TEST(OrderFit, ExactPowerLawGivesItsExponent) {
  const std::vector<double> h = steps(2, 9);
  const OrderFit fit = fit_order(h, errors(h, [](double x) { return 3.0 * std::pow(x, 4); }));
  EXPECT_NEAR(fit.slope, 4.0, 1e-12);
  EXPECT_NEAR(fit.intercept, std::log10(3.0), 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
  EXPECT_NEAR(fit.residual, 0.0, 1e-12);
  EXPECT_EQ(fit.points, 5);  // the five smallest steps
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

}  // namespace
}  // namespace rb

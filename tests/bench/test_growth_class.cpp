// The growth class of an error series (bench/lib/growth_class.hpp), on
// synthetic series sampled densely and taken as their windowed maximum, as
// the horizon study records them: t and t^2 with a little noise read back
// as linear and quadratic over three decades, a bounded series as bounded;
// a law still changing (slopes climbing 0.24, 0.49, 0.63, 0.77 a decade,
// a growth that saturates in the last decade, a bounded series that starts
// to drift 0.02 -> 0.20) is undecided, never the class of its early
// decades; fewer than three decades is undecided; a noisy decade whose
// interval leaves the band is undecided; exponential growth and rounding
// have classes of their own.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "bench/lib/growth_class.hpp"

namespace rb {
namespace {

// A small deterministic wobble in [-1, 1].
double wobble(int k) { return std::sin(12.9898 * k) * std::cos(0.7 * k); }

// err(t) at 400 points a decade from t = 1 to t_end, as its windowed
// maximum at 8 windows a decade (the horizon study's series).
GrowthFit classified(const std::function<double(double, int)>& err, double t_end, double rounding = 0.0) {
  std::vector<double> t, e;
  const int n = static_cast<int>(std::lround(400 * std::log10(t_end)));
  for (int k = 0; k <= n; ++k) {
    t.push_back(std::pow(10.0, k / 400.0));
    e.push_back(err(t.back(), k));
  }
  const auto [ends, maxima] = windowed_maximum(t, e, 8);
  return classify_growth(ends, maxima, rounding);
}

// C t^p with a relative noise of `noise`
GrowthFit power_law(double p, double noise, double t_end = 1e4) {
  return classified([&](double t, int k) { return 1e-9 * std::pow(t, p) * (1.0 + noise * wobble(k)); }, t_end);
}

// log10 err piecewise linear in log10 t with these slopes over the decades
// [1, 10], [10, 100], ...
GrowthFit piecewise(const std::vector<double>& slopes, double noise = 0.0) {
  const auto err = [&](double t, int k) {
    double log_err = -9.0, x = std::log10(t);
    for (const double s : slopes) log_err += s * std::clamp(x, 0.0, 1.0), x -= 1.0;
    return std::pow(10.0, log_err) * (1.0 + noise * wobble(k));
  };
  return classified(err, std::pow(10.0, static_cast<double>(slopes.size())));
}

TEST(GrowthClass, LinearAndQuadraticReadBackWithinTheirIntervals) {
  for (const auto& [p, expected] : {std::pair{1.0, GrowthClass::linear}, std::pair{2.0, GrowthClass::quadratic}}) {
    const GrowthFit f = power_law(p, 0.01);
    EXPECT_EQ(f.growth_class, expected) << p << ": " << f.reason;
    EXPECT_LT(std::abs(f.p - p), std::max(f.ci95, 0.01)) << f.p << " ± " << f.ci95;
    // the window: the last three decades of t, each decade's slope p
    EXPECT_DOUBLE_EQ(f.t_to, 1e4);
    EXPECT_NEAR(f.t_from, 10.0, 1e-9);
    ASSERT_EQ(f.decades.size(), 4u);  // [1, 10] .. [1000, 10^4], oldest first
    EXPECT_NEAR(f.decades.front().t_from, 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(f.decades.back().t_to, 1e4);
    for (const DecadeSlope& d : f.decades) {
      EXPECT_NEAR(d.p, p, 0.02) << d.t_from;
      EXPECT_EQ(d.points, 9);  // 8 windows a decade, both ends in
    }
    EXPECT_NEAR(f.p_last, p, 0.02);
    EXPECT_LE(std::abs(f.p_last - f.p_earlier), std::max(std::hypot(f.ci95_last, f.ci95_earlier), 0.05));
    EXPECT_FALSE(f.at_rounding);
    EXPECT_NE(f.reason.find("agree"), std::string::npos) << f.reason;
  }
  // a power between the classes is named "power" with its p
  const GrowthFit walk = power_law(0.5, 0.01);
  EXPECT_EQ(walk.growth_class, GrowthClass::power) << walk.reason;
  EXPECT_NEAR(walk.p, 0.5, 0.01);
}

TEST(GrowthClass, ABoundedSeriesOverThreeDecadesIsBounded) {
  // an oscillation of fixed amplitude: its windowed maximum is flat
  const GrowthFit f =
      classified([](double t, int k) { return 1e-6 * (1.3 + std::sin(3.0 * t) + 0.01 * wobble(k)); }, 1e4);
  EXPECT_EQ(f.growth_class, GrowthClass::bounded) << f.reason;
  EXPECT_NEAR(f.p, 0.0, 0.02);
  EXPECT_EQ(std::string(growth_class_name(f.growth_class)), "bounded");
  EXPECT_TRUE(decided(f.growth_class));
}

TEST(GrowthClass, AClimbingSeriesIsUndecided) {
  // gauss2 on gaussian-hills-chaplygin at 10^6 steps (issue 56): the old
  // two-decade fit read "asymptotic p = 0.69"
  const GrowthFit f = piecewise({0.24, 0.49, 0.63, 0.77}, 0.01);
  EXPECT_EQ(f.growth_class, GrowthClass::undecided) << f.reason;
  EXPECT_FALSE(decided(f.growth_class));
  ASSERT_EQ(f.decades.size(), 4u);
  const double slopes[] = {0.24, 0.49, 0.63, 0.77};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(f.decades[i].p, slopes[i], 0.03) << i;
  const GrowthFit exact = piecewise({0.24, 0.49, 0.63, 0.77});
  EXPECT_EQ(exact.growth_class, GrowthClass::undecided);
  EXPECT_EQ(exact.reason, "per-decade slopes 0.49, 0.63, 0.77 drift: they span 0.28 (more than 0.15)");
  // slowly climbing within the spread: the last decade is not within the
  // earlier decades' interval
  const GrowthFit slow = piecewise({0.5, 0.9, 0.96, 1.04});
  EXPECT_EQ(slow.growth_class, GrowthClass::undecided) << slow.reason;
  EXPECT_EQ(slow.reason.rfind("the last decade's slope 1.04", 0), 0u) << slow.reason;
}

TEST(GrowthClass, ASeriesThatSaturatesIsUndecidedNeverItsEarlyClass) {
  // growth t^1 over three decades, then a plateau in the last one
  const GrowthFit early = piecewise({1.0, 1.0, 1.0});
  EXPECT_EQ(early.growth_class, GrowthClass::linear) << early.reason;
  const GrowthFit f = piecewise({1.0, 1.0, 1.0, 0.0});
  EXPECT_EQ(f.growth_class, GrowthClass::undecided) << f.reason;
  EXPECT_NEAR(f.p_last, 0.0, 0.02);
  // and a bounded series that starts to drift in its last decade (dla2 at
  // 10^7 steps, 0.02 -> 0.20)
  const GrowthFit drift = piecewise({0.0, 0.0, 0.02, 0.20});
  EXPECT_EQ(drift.growth_class, GrowthClass::undecided) << drift.reason;
}

TEST(GrowthClass, FewerThanThreeDecadesIsUndecided) {
  const GrowthFit f = power_law(1.0, 0.0, 500.0);  // 2.7 decades
  EXPECT_EQ(f.growth_class, GrowthClass::undecided);
  EXPECT_EQ(f.reason, "the samples span 2 whole decades of t; a class needs 3");
  EXPECT_EQ(f.decades.size(), 2u);
  EXPECT_NEAR(f.p, 1.0, 1e-6);  // the exponent is still fitted and reported
  // three decades: decided
  EXPECT_EQ(power_law(1.0, 0.0, 1000.0).growth_class, GrowthClass::linear);
}

TEST(GrowthClass, ANoisyDecadeLeavesItsClassUndecided) {
  // raw samples, flat on average but 60 % noise: the decades' slopes are
  // too uncertain (or too far apart) for a class
  const GrowthFit f = classified([](double, int k) { return 1e-6 * (1.0 + 0.4 * wobble(k)); }, 1e4);
  std::vector<double> t, e;
  for (int k = 0; k <= 32; ++k) t.push_back(std::pow(10.0, k / 8.0)), e.push_back(1e-6 * (1.0 + 0.6 * wobble(k)));
  const GrowthFit raw = classify_growth(t, e, 0.0);
  EXPECT_EQ(raw.growth_class, GrowthClass::undecided) << raw.reason;
  // the windowed maximum of the same kind of noise is flat: bounded
  EXPECT_EQ(f.growth_class, GrowthClass::bounded) << f.reason;
}

TEST(GrowthClass, ExponentialGrowthAndRoundingHaveClassesOfTheirOwn) {
  const GrowthFit e = classified([](double t, int) { return 1e-12 * std::exp(t / 300.0); }, 1e4);
  EXPECT_EQ(e.growth_class, GrowthClass::exponential) << e.reason;
  // a steep power law keeps one slope: power, not exponential
  EXPECT_EQ(power_law(4.0, 0.0).growth_class, GrowthClass::power);
  const GrowthFit r = classified([](double, int k) { return 1e-14 * (1.5 + wobble(k)); }, 1e4, 1e-12);
  EXPECT_EQ(r.growth_class, GrowthClass::rounding) << r.reason;
  EXPECT_TRUE(r.at_rounding);
  // zeros: at rounding, no slope
  const GrowthFit zeros = classified([](double, int) { return 0.0; }, 1e4, 1e-12);
  EXPECT_EQ(zeros.growth_class, GrowthClass::rounding);
  EXPECT_TRUE(std::isnan(zeros.p));
  // no value at all: no class
  const GrowthFit none = classified([](double, int) { return kNaN; }, 1e4);
  EXPECT_EQ(none.growth_class, GrowthClass::none);
  EXPECT_EQ(none.reason, "no finite value in the window");
}

TEST(GrowthClass, TheWindowedMaximumIsTheLargestInEachWindow) {
  // windows (.., 1], (1, 10^0.5], (10^0.5, 10], (10, 20] at 2 a decade
  const std::vector<double> t = {1, 2, 3, 4, 5, 9, 10, 15, 20};
  const std::vector<double> e = {7, 1, 5, 2, kNaN, 3, 4, 1, 0.5};
  const auto [ends, maxima] = windowed_maximum(t, e, 2);
  ASSERT_EQ(ends.size(), 4u);
  EXPECT_NEAR(ends[1], std::sqrt(10.0), 1e-12);
  EXPECT_EQ(ends.back(), 20.0);
  const std::vector<double> expected = {7, 5, 4, 1};
  EXPECT_EQ(maxima, expected);
  // a window with no finite value is NaN
  const auto [ends2, maxima2] = windowed_maximum({1, 2, 20}, {1, kNaN, 2}, 2);
  ASSERT_EQ(maxima2.size(), 4u);
  EXPECT_TRUE(std::isnan(maxima2[1]) && std::isnan(maxima2[2]));
  EXPECT_EQ(maxima2[3], 2.0);
}

}  // namespace
}  // namespace rb

#include "bench/lib/growth_class.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bench/lib/order_fit.hpp"

namespace rb {

namespace {

std::string fixed(double v, const char* format = "%.2f") {
  if (!std::isfinite(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

std::string with_ci(double p, double ci) { return fixed(p) + " ± " + fixed(ci); }

// the slack keeps a window edge that is a sample time itself in it
bool within(double t, double from, double to) { return t >= from * (1 - 1e-12) && t <= to * (1 + 1e-12); }

// log10 of the pairs with t in [from, to] and err finite and > 0
struct LogPoints {
  std::vector<double> x, y;
};
LogPoints log_points(const std::vector<double>& t, const std::vector<double>& err, double from, double to) {
  LogPoints p;
  for (std::size_t i = 0; i < t.size() && i < err.size(); ++i)
    if (within(t[i], from, to) && std::isfinite(err[i]) && err[i] > 0.0)
      p.x.push_back(std::log10(t[i])), p.y.push_back(std::log10(err[i]));
  return p;
}

// The class whose band holds p, and the band.
struct Band {
  GrowthClass c;
  double lo, hi;
};
Band band_of(double p, double w) {
  if (p <= w) return {GrowthClass::bounded, -std::numeric_limits<double>::infinity(), w};
  if (p < 1 - w) return {GrowthClass::power, w, 1 - w};
  if (p <= 1 + w) return {GrowthClass::linear, 1 - w, 1 + w};
  if (p < 2 - w) return {GrowthClass::power, 1 + w, 2 - w};
  if (p <= 2 + w) return {GrowthClass::quadratic, 2 - w, 2 + w};
  return {GrowthClass::power, 2 + w, std::numeric_limits<double>::infinity()};
}

std::string band_text(const Band& b) {
  if (!std::isfinite(b.lo)) return "p <= " + fixed(b.hi);
  if (!std::isfinite(b.hi)) return "p > " + fixed(b.lo);
  return fixed(b.lo) + " .. " + fixed(b.hi);
}

std::string slopes_text(const std::vector<DecadeSlope>& d, std::size_t from) {
  std::string s;
  for (std::size_t i = from; i < d.size(); ++i) s += (s.empty() ? "" : ", ") + fixed(d[i].p);
  return s;
}

std::string decade_text(const DecadeSlope& d) {
  return "t = " + fixed(d.t_from, "%.4g") + " .. " + fixed(d.t_to, "%.4g");
}

}  // namespace

const char* growth_class_name(GrowthClass c) {
  switch (c) {
    case GrowthClass::none: return "none";
    case GrowthClass::undecided: return "undecided";
    case GrowthClass::rounding: return "rounding";
    case GrowthClass::bounded: return "bounded";
    case GrowthClass::linear: return "linear";
    case GrowthClass::quadratic: return "quadratic";
    case GrowthClass::power: return "power";
    case GrowthClass::exponential: return "exponential";
  }
  return "none";
}

bool decided(GrowthClass c) { return c != GrowthClass::none && c != GrowthClass::undecided; }

GrowthFit classify_growth(const std::vector<double>& t, const std::vector<double>& err, double rounding,
                          const GrowthRules& rules) {
  GrowthFit f;
  f.rounding_level = rounding;
  double t_min = std::numeric_limits<double>::infinity();
  for (const double v : t)
    if (v > 0.0 && std::isfinite(v)) t_min = std::min(t_min, v), f.t_to = std::max(f.t_to, v);
  if (!(f.t_to > 0.0)) {
    f.reason = "no time > 0 in the series";
    return f;
  }
  const int w = std::max(1, rules.decades);
  f.t_from = f.t_to * std::pow(10.0, -w);
  // the decades back from t_to while the samples reach their start
  for (int k = 0; within(t_min, 0.0, f.t_to * std::pow(10.0, -(k + 1))); ++k) {
    DecadeSlope d;
    d.t_to = f.t_to * std::pow(10.0, -k);
    d.t_from = d.t_to / 10.0;
    const LogPoints p = log_points(t, err, d.t_from, d.t_to);
    d.points = static_cast<int>(p.x.size());
    if (d.points >= kMinGrowthPoints) {
      const LineFit l = fit_line(p.x, p.y);
      d.p = l.slope, d.ci95 = l.slope_ci95;
    }
    f.decades.insert(f.decades.begin(), d);
  }
  for (std::size_t i = 0; i < t.size() && i < err.size(); ++i)
    if (within(t[i], f.t_from, f.t_to) && std::isfinite(err[i]) && !(f.largest >= err[i])) f.largest = err[i];
  f.at_rounding = std::isfinite(f.largest) && f.largest <= rounding;
  const LogPoints all = log_points(t, err, f.t_from, f.t_to);
  f.points = static_cast<int>(all.x.size());
  if (f.points >= kMinGrowthPoints) {
    const LineFit l = fit_line(all.x, all.y);
    f.p = l.slope, f.ci95 = l.slope_ci95, f.log10_c = l.intercept;
  }
  const std::size_t n = f.decades.size(), window = static_cast<std::size_t>(w);
  if (n >= window) {
    const DecadeSlope& last = f.decades.back();
    f.p_last = last.p, f.ci95_last = last.ci95;
    const LogPoints earlier = log_points(t, err, f.t_from, last.t_from);
    if (w > 1 && static_cast<int>(earlier.x.size()) >= kMinGrowthPoints) {
      const LineFit l = fit_line(earlier.x, earlier.y);
      f.p_earlier = l.slope, f.ci95_earlier = l.slope_ci95;
    }
  }
  const auto verdict = [&](GrowthClass c, std::string why) {
    f.growth_class = c;
    f.reason = std::move(why);
    return f;
  };
  if (!std::isfinite(f.largest)) return verdict(GrowthClass::none, "no finite value in the window");
  if (n < window)
    return verdict(GrowthClass::undecided, "the samples span " + std::to_string(n) + " whole decade" +
                                               (n == 1 ? "" : "s") + " of t; a class needs " + std::to_string(w));
  if (f.at_rounding)
    return verdict(GrowthClass::rounding, "the largest value in the window, " + fixed(f.largest, "%.3g") +
                                              ", is at most the rounding level " + fixed(rounding, "%.3g"));
  for (std::size_t i = n - window; i < n; ++i)
    if (!std::isfinite(f.decades[i].p))
      return verdict(GrowthClass::undecided, "the decade " + decade_text(f.decades[i]) + " has " +
                                                 std::to_string(f.decades[i].points) + " values > 0 (a slope needs " +
                                                 std::to_string(kMinGrowthPoints) + ")");
  const std::string slopes = "per-decade slopes " + slopes_text(f.decades, n - window);
  // exponential: a slope that keeps rising, faster and faster
  bool rising = true;
  for (std::size_t i = n - window + 1; i < n; ++i) rising = rising && f.decades[i].p > f.decades[i - 1].p;
  if (window >= 2 && rising && f.p_last >= rules.exponential_slope && f.p_last >= 1.5 * f.decades[n - 2].p)
    return verdict(GrowthClass::exponential, slopes + ": rising, the last " + fixed(f.p_last) + " at least " +
                                                 fixed(rules.exponential_slope) + " and 1.5 times the one before");
  double lo = f.decades[n - window].p, hi = lo;
  for (std::size_t i = n - window; i < n; ++i) lo = std::min(lo, f.decades[i].p), hi = std::max(hi, f.decades[i].p);
  if (hi - lo > rules.spread)
    return verdict(GrowthClass::undecided,
                   slopes + " drift: they span " + fixed(hi - lo) + " (more than " + fixed(rules.spread) + ")");
  if (w > 1) {
    const double tolerance = std::max(std::hypot(f.ci95_earlier, f.ci95_last), rules.resolution);
    if (!(std::abs(f.p_last - f.p_earlier) <= tolerance))
      return verdict(GrowthClass::undecided, "the last decade's slope " + with_ci(f.p_last, f.ci95_last) +
                                                 " is not within the earlier decades' " +
                                                 with_ci(f.p_earlier, f.ci95_earlier) + " (" + slopes + ")");
  }
  const Band band = band_of(f.p, rules.band);
  for (std::size_t i = n - window; i < n; ++i) {
    const DecadeSlope& d = f.decades[i];
    if (!(d.p - d.ci95 >= band.lo && d.p + d.ci95 <= band.hi))
      return verdict(GrowthClass::undecided, "the slope over " + decade_text(d) + ", " + with_ci(d.p, d.ci95) +
                                                 ", reaches out of the " + growth_class_name(band.c) + " band " +
                                                 band_text(band) + " (" + slopes + ")");
  }
  return verdict(band.c, slopes + " agree (span " + fixed(hi - lo) + "), the last within the earlier decades' " +
                             with_ci(f.p_earlier, f.ci95_earlier) + ", each in the " + growth_class_name(band.c) +
                             " band " + band_text(band));
}

std::pair<std::vector<double>, std::vector<double>> windowed_maximum(const std::vector<double>& t,
                                                                     const std::vector<double>& err, int per_decade) {
  std::pair<std::vector<double>, std::vector<double>> out;
  if (t.empty() || !(t.front() > 0.0) || per_decade < 1) return out;
  std::vector<double>& ends = out.first;
  for (int k = 0;; ++k) {
    const double end = t.front() * std::pow(10.0, static_cast<double>(k) / per_decade);
    if (end >= t.back() * (1 - 1e-12)) break;
    ends.push_back(end);
  }
  ends.push_back(t.back());
  out.second.assign(ends.size(), kNaN);
  std::size_t w = 0;
  for (std::size_t i = 0; i < t.size() && i < err.size(); ++i) {
    while (w < ends.size() && t[i] > ends[w] * (1 + 1e-12)) ++w;
    if (w == ends.size()) break;
    double& largest = out.second[w];
    if (std::isfinite(err[i]) && !(largest >= err[i])) largest = err[i];
  }
  return out;
}

}  // namespace rb

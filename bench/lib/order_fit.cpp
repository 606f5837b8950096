#include "bench/lib/order_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rb {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An observed order this far below the declared one still counts as it.
constexpr double kOrderTolerance = 0.2;
// Slopes settling onto the declared order from above may end this far
// below it: the falls' ratio is read from two of them.
constexpr double kSettlingTolerance = 0.05;
// A trend of less than this per halving moves the slope by 0.02 over four
// halvings: no fall (rk3's slopes on bowl-3d, 3.000 at every halving, have
// a trend of 1e-4 whose interval is narrower still).
constexpr double kNegligibleTrend = 0.005;
// What a reference 100 x below (kFloorMultiple) can take off the slope of
// the last halving before the plateau: log2(1 + 1/100) = 0.014, with room.
constexpr double kPlateauMargin = 0.02;
// A wider 95 % interval decides nothing.
constexpr double kMaxHalfWidth = 0.3;

using Points = std::vector<std::pair<double, double>>;

// two-sided 95 % Student t quantile for dof degrees of freedom
double t95(int dof) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228};
  if (dof <= 0) return std::numeric_limits<double>::infinity();
  return dof <= 10 ? table[dof - 1] : 1.96 + 2.5 / dof;
}

// ordinary least squares of y on x over p[lo, hi)
LineFit least_squares(const Points& p, std::size_t lo, std::size_t hi) {
  LineFit l;
  l.points = static_cast<int>(hi - lo);
  l.slope = kNaN;
  if (hi - lo < 2) return l;
  const double n = static_cast<double>(hi - lo);
  double sx = 0, sy = 0;
  for (std::size_t i = lo; i < hi; ++i) sx += p[i].first, sy += p[i].second;
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    const double dx = p[i].first - mx, dy = p[i].second - my;
    sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
  }
  if (!(sxx > 0)) return l;
  l.slope = sxy / sxx;
  l.intercept = my - l.slope * mx;
  // residuals summed directly: syy - slope sxy cancels to noise on a good fit
  double sse = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    const double r = p[i].second - (l.intercept + l.slope * p[i].first);
    sse += r * r;
  }
  l.r2 = syy > 0 ? 1.0 - sse / syy : 1.0;
  l.residual = std::sqrt(sse / n);
  l.slope_ci95 = t95(l.points - 2) * (n > 2 ? std::sqrt(sse / (n - 2) / sxx) : 0.0);
  return l;
}

double local_slope_between(const Points& p, std::size_t i, std::size_t j) {
  return (p[j].second - p[i].second) / (p[j].first - p[i].first);
}

double local_slope(const Points& p, std::size_t i) { return local_slope_between(p, i, i + 1); }

// The local slopes from the smallest step up, each from a point to the
// first whose step is between lowest and highest times its own (within 10 %:
// at large h the steps taken, t_end / ceil(t_end / h), are off the ladder's
// values; the slope uses the ratio itself), count at most; fewer where the
// ladder has no such point. lowest = highest = 2: the halving slopes;
// lowest sqrt(2): the rung slopes.
std::vector<double> slopes_over(const Points& p, double lowest, double highest, int count) {
  std::vector<double> slopes;
  const double slack = std::log10(1.1), low = std::log10(lowest) - slack, high = std::log10(highest) + slack;
  std::size_t i = 0;
  while (slopes.size() < static_cast<std::size_t>(count)) {
    std::size_t j = i + 1;
    while (j < p.size() && p[j].first < p[i].first + low) ++j;
    if (j == p.size() || p[j].first > p[i].first + high) break;
    slopes.push_back(local_slope_between(p, i, j));
    i = j;
  }
  return slopes;
}

// True when slopes v (smallest step first) settle onto the declared order
// from above: the smallest step's at least declared - margin, the last fall
// no larger than the one before it (two slopes: taken as twice it), and the
// falls still to come, shrinking at that ratio, leave the slope within
// kSettlingTolerance of the declared order.
bool settles_onto(const std::vector<double>& v, int declared, double margin) {
  if (v.size() < 2 || !(v[0] >= declared - margin)) return false;
  const double last_fall = v[1] - v[0];
  if (last_fall <= 0.0) return true;
  const double before = v.size() >= 3 ? v[2] - v[1] : 2.0 * last_fall;
  if (last_fall > before) return false;
  const double ratio = last_fall / before;
  return ratio < 1.0 && v[0] - last_fall * ratio / (1.0 - ratio) >= declared - kSettlingTolerance;
}

}  // namespace

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  Points p;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i])) p.emplace_back(x[i], y[i]);
  return least_squares(p, 0, p.size());
}

double plateau_level(double floor, double rounding_step, double h) {
  return rounding_step > 0.0 && h > 0.0 && h < rounding_step ? floor * (rounding_step / h) : floor;
}

LineFit trend_of(const std::vector<double>& slopes) {
  // x: the halving index towards small steps (the smallest step's slope at 0)
  std::vector<double> x, y;
  for (std::size_t i = 0; i < slopes.size(); ++i) x.push_back(-static_cast<double>(i)), y.push_back(slopes[i]);
  LineFit line = fit_line(x, y);
  if (line.points < 3) line.slope = line.slope_ci95 = kNaN;
  return line;
}

OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& error, double floor, double ceiling,
                   std::size_t max_points, double rounding_step) {
  Points all;  // (h, error), by h ascending
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i)
    if (h[i] > 0.0) all.emplace_back(h[i], error[i]);
  std::sort(all.begin(), all.end());
  // from the smallest step up, until the error passes the ceiling: a lucky
  // small error at a larger step beyond that is not asymptotic
  Points p;  // (log10 h, log10 error)
  int at_floor = 0;
  // a failed run has no error: it neither makes nor breaks "exact" (its
  // failure is reported on its own)
  bool all_on_plateau = true;
  bool past_ceiling = false;
  int above_ceiling = 0;
  int failed = 0;
  for (const auto& [step, e] : all) {
    const double plateau = kFloorMultiple * plateau_level(floor, rounding_step, step);
    all_on_plateau = all_on_plateau && (!std::isfinite(e) || e <= plateau);
    if (!std::isfinite(e)) ++failed;
    if (past_ceiling || e > ceiling) {
      past_ceiling = true;
      if (std::isfinite(e)) ++above_ceiling;
      continue;
    }
    if (std::isfinite(e) && e > plateau && e > 0.0) p.emplace_back(std::log10(step), std::log10(e));
    else if (std::isfinite(e)) ++at_floor;
  }
  OrderFit fit;
  fit.slope = kNaN;
  fit.points = static_cast<int>(p.size());
  fit.at_floor = at_floor;
  fit.above_ceiling = above_ceiling;
  fit.failed = failed;
  fit.smallest_finite = !all.empty() && std::isfinite(all.front().second);
  fit.all_at_plateau = all_on_plateau && at_floor >= kMinOrderPoints;
  if (p.size() < 2) return fit;

  fit.trend_slopes = slopes_over(p, 2.0, 2.0, kTrendSlopes);
  fit.halving_slopes.assign(
      fit.trend_slopes.begin(),
      fit.trend_slopes.begin() + std::min<std::ptrdiff_t>(kHalvingSlopes, fit.trend_slopes.size()));
  fit.rung_slopes = slopes_over(p, std::sqrt(2.0), 2.0, kHalvingSlopes);
  const LineFit trend = trend_of(fit.trend_slopes);
  fit.trend = trend.slope;
  fit.trend_ci95 = trend.slope_ci95;
  fit.asymptotic =
      fit.halving_slopes.size() == static_cast<std::size_t>(kHalvingSlopes) && slopes_agree(fit.halving_slopes);
  const std::size_t min_points = static_cast<std::size_t>(kMinOrderPoints);
  const std::size_t lo = 0;
  // a caller may ask for fewer points than a verdict needs (a slope alone)
  max_points = std::max<std::size_t>(2, max_points);
  std::size_t hi = std::min(p.size(), lo + std::min(min_points, max_points));
  while (hi < p.size() && hi - lo < max_points) {
    const LineFit window = least_squares(p, lo, hi);
    const double tolerance = std::max(0.15, 0.05 * std::abs(window.slope));
    // clean data: the next point's local slope agrees with the window's;
    // noisy data (an interval wider than that): the fit with the next point
    // stays inside the window's own interval, so a longer window narrows
    // the interval without moving the slope out of it
    const bool agrees = std::abs(local_slope(p, hi - 1) - window.slope) <= tolerance;
    const bool within = window.slope_ci95 > tolerance &&
                        std::abs(least_squares(p, lo, hi + 1).slope - window.slope) <= window.slope_ci95;
    if (!agrees && !within) break;
    ++hi;
  }
  const LineFit l = least_squares(p, lo, hi);
  fit.slope = l.slope;
  fit.intercept = l.intercept;
  fit.r2 = l.r2;
  fit.residual = l.residual;
  fit.points = l.points;
  fit.slope_ci95 = l.slope_ci95;
  fit.h_min = std::pow(10.0, p[lo].first);
  fit.h_max = std::pow(10.0, p[hi - 1].first);
  return fit;
}

bool slopes_agree(const std::vector<double>& slopes) {
  if (slopes.empty()) return false;
  const auto [least, most] = std::minmax_element(slopes.begin(), slopes.end());
  const double middle = 0.5 * (*least + *most);
  return 0.5 * (*most - *least) <= std::max(kHalvingAgreement, 0.05 * std::abs(middle));
}

bool falling(const OrderFit& fit, int declared) {
  const std::vector<double>& s = fit.trend_slopes;
  if (s.size() < 2) return false;
  // a trend whose whole interval lies below -kNegligibleTrend
  if (!(fit.trend + fit.trend_ci95 < -kNegligibleTrend)) return false;
  // unless the slopes settle onto the declared order from above; next to
  // the plateau, whose own error may take kPlateauMargin off the last
  // halving, from that far below it
  return !settles_onto(s, declared, fit.at_floor > 0 ? kPlateauMargin : 0.0);
}

bool slopes_in_band(const OrderFit& fit, double bar) {
  // the most local slope at the smallest step: over its half-octave rung
  // where the ladder has one, over its halving elsewhere
  const std::vector<double>& s = !fit.rung_slopes.empty() ? fit.rung_slopes : fit.halving_slopes;
  if (s.empty()) return true;
  if (s[0] < bar) return false;
  // where more halvings can run: the last fall, carried on for one more
  // halving, stays in the band
  return fit.at_floor > 0 || s.size() < 2 || s[0] - std::max(0.0, s[1] - s[0]) >= bar;
}

bool climbing_to(const OrderFit& fit, double bar) {
  const std::vector<double>& s = fit.halving_slopes;
  if (s.empty()) return false;
  if (s[0] >= bar || (s.size() >= 2 && s[0] + (s[0] - s[1]) >= bar)) return true;
  // a rising trend: at most its interval's upper end more
  return fit.trend > 0.0 && s[0] + fit.trend + fit.trend_ci95 >= bar;
}

bool pre_asymptotic(const OrderFit& fit) {
  return fit.points >= kMinOrderPoints && std::isfinite(fit.slope) && !fit.asymptotic;
}

bool wants_finer_steps(const OrderFit& fit, int declared) {
  if (fit.at_floor > 0) return false;
  const std::string why = inconclusive_reason(fit, declared);
  if (why == "too few points")
    // a ladder of enough runs that ends before its errors come under the
    // ceiling; not a short ladder the user chose, nor runs that failed
    return fit.smallest_finite && fit.above_ceiling > 0 && fit.points + fit.above_ceiling >= kMinOrderPoints;
  // an interval too wide to decide while the slopes still move: finer
  // steps reach the asymptotic range, where the slope settles
  if (why == "wide interval") return !fit.asymptotic;
  return why == "pre-asymptotic" || why == "straddles";
}

std::string inconclusive_reason(const OrderFit& fit, int declared) {
  if (order_verdict(fit, declared) != "inconclusive") return "";
  if (fit.points < kMinOrderPoints || !std::isfinite(fit.slope)) {
    if (fit.at_floor > 0 && fit.points + fit.at_floor >= kMinOrderPoints) return "floor";
    // the runs that have an error are too few even with those above the
    // ceiling, and the rest failed
    const bool failures = fit.failed > 0 && fit.points + fit.at_floor + fit.above_ceiling < kMinOrderPoints &&
                          fit.points + fit.failed >= kMinOrderPoints;
    return failures ? "failed runs" : "too few points";
  }
  const double bar = declared - kOrderTolerance;
  const bool above = fit.slope - fit.slope_ci95 >= bar;
  if (!(fit.slope_ci95 <= kMaxHalfWidth) && !above) return "wide interval";
  // the slope still moves: it falls away from the declared order, the
  // halvings disagree, the last slopes leave the band under a window above
  // it, or an interval below the bar whose slope still climbs towards it
  const bool below = fit.slope + fit.slope_ci95 < bar;
  const bool moving = falling(fit, declared) || pre_asymptotic(fit) || (above && !slopes_in_band(fit, bar)) ||
                      (below && climbing_to(fit, bar));
  if (moving) return fit.at_floor == 0 ? "pre-asymptotic" : "no asymptotic range above the plateau";
  return "straddles";
}

bool certified_at_plateau(const OrderFit& fit, double bar) {
  if (fit.at_floor == 0) return false;
  // slopes that settle onto the declared order from above (settles_onto),
  // none below it by more than kPlateauMargin
  const int declared = static_cast<int>(std::lround(bar + kOrderTolerance));
  const auto settles = [&](const std::vector<double>& v) {
    return v.size() >= 3 && *std::min_element(v.begin(), v.end()) >= declared - kPlateauMargin &&
           settles_onto(v, declared, kPlateauMargin);
  };
  // two halvings that reach the bar and do not fall towards small steps by
  // more than the agreement (or settle), under a window whose interval lies
  // above the bar
  const std::vector<double>& s = fit.halving_slopes;
  const bool halvings = s.size() >= 2 &&
                        (s[0] >= s[1] - std::max(kHalvingAgreement, 0.05 * std::abs(s[1])) || settles(s)) &&
                        std::min(s[0], s[1]) >= bar && fit.slope - fit.slope_ci95 >= bar;
  // or rungs: the smallest step's rung slope reaches the bar, and none of
  // the rungs above it lies higher by more than the agreement (a slope
  // still climbing towards its order as h falls, or level), or they settle
  const std::vector<double>& r = fit.rung_slopes;
  if (halvings || r.size() < 2 || !(r[0] >= bar)) return halvings;
  const double highest = *std::max_element(r.begin() + 1, r.end());
  return r[0] >= highest - std::max(kHalvingAgreement, 0.05 * std::abs(highest)) || settles(r);
}

std::string order_verdict(const OrderFit& fit, int declared) {
  if (fit.all_at_plateau) return "exact";
  if (fit.points < kMinOrderPoints || !std::isfinite(fit.slope)) return "inconclusive";
  const double bar = declared - kOrderTolerance;
  const bool above = fit.slope - fit.slope_ci95 >= bar, wide = !(fit.slope_ci95 <= kMaxHalfWidth);
  // a pass needs the last slopes inside the band and slopes that do not
  // fall away from the declared order: more halvings could take them out
  if (!falling(fit, declared) && slopes_in_band(fit, bar)) {
    if (fit.asymptotic && above) return "as declared";
    // a wide interval certifies only where all of it lies above the bar
    if ((above || !wide) && certified_at_plateau(fit, bar)) return "as declared";
  }
  // a wider interval, moving slopes or a window above the bar condemn nothing
  if (wide || pre_asymptotic(fit) || above) return "inconclusive";
  // a slope still climbing towards the bar at the smallest steps is not
  // yet the method's: no lower verdict before it stops
  if (fit.slope + fit.slope_ci95 < bar) return climbing_to(fit, bar) ? "inconclusive" : "lower";
  return "inconclusive";  // an interval that holds the bar
}

OrderJudgement judge_order(const OrderFit& reference, const OrderFit& self, int declared) {
  const std::string by_reference = order_verdict(reference, declared);
  if (by_reference == "inconclusive") return {by_reference, inconclusive_reason(reference, declared)};
  // no slope to confirm: the runs' own differences sit at rounding too
  if (by_reference == "exact") return {by_reference, ""};
  if (!std::isfinite(self.slope)) return {"inconclusive", "no self-convergence"};
  if (std::abs(self.slope - reference.slope) > std::max(kSelfAgreement, 0.05 * declared))
    return {"inconclusive", "self-convergence disagrees"};
  return {by_reference, ""};
}

}  // namespace rb

#include "bench/lib/order_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rb {

namespace {

struct Line {
  double slope, intercept, r2, se_slope, rms;
};

// ordinary least squares of y on x
Line least_squares(const std::vector<std::pair<double, double>>& p, std::size_t lo, std::size_t hi) {
  const double n = static_cast<double>(hi - lo);
  double sx = 0, sy = 0;
  for (std::size_t i = lo; i < hi; ++i) sx += p[i].first, sy += p[i].second;
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    const double dx = p[i].first - mx, dy = p[i].second - my;
    sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
  }
  Line l;
  l.slope = sxy / sxx;
  l.intercept = my - l.slope * mx;
  // residuals summed directly: syy - slope sxy cancels to noise on a good fit
  double sse = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    const double r = p[i].second - (l.intercept + l.slope * p[i].first);
    sse += r * r;
  }
  l.r2 = syy > 0 ? 1.0 - sse / syy : 1.0;
  l.se_slope = n > 2 ? std::sqrt(sse / (n - 2) / sxx) : 0.0;
  l.rms = std::sqrt(sse / n);
  return l;
}

// two-sided 95 % Student t quantile for dof degrees of freedom
double t95(int dof) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228};
  if (dof <= 0) return std::numeric_limits<double>::infinity();
  return dof <= 10 ? table[dof - 1] : 1.96 + 2.5 / dof;
}

double local_slope(const std::vector<std::pair<double, double>>& p, std::size_t i) {
  return (p[i + 1].second - p[i].second) / (p[i + 1].first - p[i].first);
}

}  // namespace

OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& error, double floor, double ceiling,
                   std::size_t max_points) {
  std::vector<std::pair<double, double>> all;  // (h, error), by h ascending
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i)
    if (h[i] > 0.0) all.emplace_back(h[i], error[i]);
  std::sort(all.begin(), all.end());
  // from the smallest step up, until the error passes the ceiling: a lucky
  // small error at a larger step beyond that is not asymptotic
  std::vector<std::pair<double, double>> p;  // (log10 h, log10 error)
  for (const auto& [step, e] : all) {
    if (e > ceiling) break;
    if (std::isfinite(e) && e > 10.0 * floor && e > 0.0) p.emplace_back(std::log10(step), std::log10(e));
  }
  OrderFit fit;
  fit.slope = std::numeric_limits<double>::quiet_NaN();
  if (p.size() < 2) return fit;

  std::size_t lo = 0, hi = p.size();
  while (hi - lo > 3) {
    const double rest_small = least_squares(p, lo + 1, hi).slope;  // without the smallest h
    const double rest_large = least_squares(p, lo, hi - 1).slope;  // without the largest h
    const double dev_small = std::abs(local_slope(p, lo) - rest_small);
    const double dev_large = std::abs(local_slope(p, hi - 2) - rest_large);
    const double tol_small = std::max(0.15, 0.3 * std::abs(rest_small));
    const double tol_large = std::max(0.15, 0.3 * std::abs(rest_large));
    if (dev_small / tol_small >= dev_large / tol_large && dev_small > tol_small) {
      ++lo;
    } else if (dev_large > tol_large) {
      --hi;
    } else {
      break;
    }
  }
  // the asymptotic range is where h is small: of a long consistent run keep
  // the smallest steps, so that pre-asymptotic curvature does not bias it
  max_points = std::max<std::size_t>(2, max_points);
  if (hi - lo > max_points) hi = lo + max_points;
  const Line l = least_squares(p, lo, hi);
  fit.slope = l.slope;
  fit.intercept = l.intercept;
  fit.r2 = l.r2;
  fit.residual = l.rms;
  fit.points = static_cast<int>(hi - lo);
  fit.slope_ci95 = t95(fit.points - 2) * l.se_slope;
  fit.h_min = std::pow(10.0, p[lo].first);
  fit.h_max = std::pow(10.0, p[hi - 1].first);
  return fit;
}

}  // namespace rb

#pragma once
// Observed order of convergence: the least-squares slope of log(error)
// against log(h) over the asymptotic range, i.e. without the pre-asymptotic
// large steps and without the points that sit on a floor (rounding, or the
// reference's own error); its verdict against the declared order; and the
// straight-line fit that tolerance proportionality uses.
#include <string>
#include <vector>

namespace rb {

// A least-squares line y = slope x + intercept.
struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  double r2 = 0.0;          // coefficient of determination
  double residual = 0.0;    // root-mean-square residual of y about the line
  double slope_ci95 = 0.0;  // half-width of the 95 % confidence interval of the slope (inf below 3 points)
  int points = 0;
};

// The fit of the finite (x, y) pairs; slope NaN below two points or when
// every x is the same.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

struct OrderFit {
  double slope = 0.0;       // observed order p in error ~ C h^p; NaN when no fit
  double intercept = 0.0;   // log10(C)
  double r2 = 0.0;          // coefficient of determination of the fit
  double residual = 0.0;    // root-mean-square residual of log10(error) about the line
  double slope_ci95 = 0.0;  // half-width of the 95 % confidence interval of the slope
  double h_min = 0.0, h_max = 0.0;
  int points = 0;
  int at_floor = 0;  // measured points left out for lying at or below 10 * floor
};

// A verdict needs at least this many points in its window.
inline constexpr int kMinOrderPoints = 4;

// h and error are paired. Points with a non-finite error or an error below
// 10 * floor are left out, and so is every point from the smallest h whose
// error passes ceiling upward (pre-asymptotic: a rotation angle or a length
// of the scene's unit size has nothing left to converge). The window then
// starts at the smallest steps, where the expansion in h holds best: the
// smallest h is dropped while its local slope is below half that of the
// rest (a rounding plateau), the window takes the kMinOrderPoints smallest
// steps left, and a larger step joins it only while the local slope up to
// it stays within max(0.15, 0.05 p) of the window's slope p or, where the
// window's 95 % interval is wider than that (noisy errors), while the fit
// with it stays inside that interval; up to max_points (below
// kMinOrderPoints: that many, a slope without a verdict). So
// pre-asymptotic large steps, whose slope drifts, stay out, and a verdict
// rests on a slope its own interval does not contradict.
OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& error, double floor = 0.0,
                   double ceiling = 0.1, std::size_t max_points = 6);

// "as declared" when the 95 % interval of the slope lies above declared -
// 0.2, "lower" when it lies below, "inconclusive" when it straddles that,
// is wider than +-0.3 or rests on fewer than kMinOrderPoints points.
std::string order_verdict(const OrderFit& fit, int declared);

// Why a verdict is inconclusive: "too few points" (below kMinOrderPoints in
// the window, or no fit), "floor" (as few, but only because points reached
// the reference's floor: a finer ladder at large h would give them),
// "wide interval" (half-width above 0.3) or "straddles" (the interval holds
// declared - 0.2); empty for a verdict.
std::string inconclusive_reason(const OrderFit& fit, int declared);

}  // namespace rb

#pragma once
// Observed order of convergence: the least-squares slope of log(error)
// against log(h) over the asymptotic range, i.e. without the pre-asymptotic
// large steps and without the points that sit on a floor (rounding, or the
// reference's own error).
#include <vector>

namespace rb {

struct OrderFit {
  double slope = 0.0;      // observed order p in error ~ C h^p; NaN when no fit
  double intercept = 0.0;  // log10(C)
  double r2 = 0.0;         // coefficient of determination of the fit
  double residual = 0.0;   // root-mean-square residual of log10(error) about the line
  double slope_ci95 = 0.0; // half-width of the 95 % confidence interval of the slope
  double h_min = 0.0, h_max = 0.0;
  int points = 0;
};

// h and error are paired. Points with a non-finite error or an error below
// 10 * floor are left out, and so is every point from the smallest h whose
// error passes ceiling upward (pre-asymptotic: a rotation angle or a length
// of the scene's unit size has nothing left to converge). Then, while more
// than three points remain, the end whose local slope disagrees most (by
// more than 0.3 times the slope of the rest, at least 0.15) with the rest is
// dropped. Of what remains, at most max_points of the smallest steps are
// fitted: the asymptotic range is where h is small.
OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& error, double floor = 0.0,
                   double ceiling = 0.1, std::size_t max_points = 5);

}  // namespace rb

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
  int at_floor = 0;  // measured points left out on the plateau (kFloorMultiple, kRoundingMultiple)
  // finite errors left out above the ceiling, from the first step up whose
  // error passes it; smallest_finite: the smallest step's error is finite
  int above_ceiling = 0;
  bool smallest_finite = false;
  int failed = 0;  // runs of the ladder without a finite error (they failed)
  // the local slopes over successive halvings of h from the smallest step
  // kept up (at most kHalvingSlopes): where they still move, the smallest
  // steps are not yet asymptotic
  std::vector<double> halving_slopes;
  // the local slopes over successive rungs from the smallest step kept up:
  // each to the first step at least sqrt(2) and at most 2 times its own
  // (within 10 %), kHalvingSlopes at most; half octaves where the ladder has
  // them (the quarter-step part of the default ladder), halvings elsewhere
  std::vector<double> rung_slopes;
  bool asymptotic = false;  // kHalvingSlopes halving slopes agree (slopes_agree)
  // every step's error is on the plateau (runs that failed have none), at
  // kMinOrderPoints steps or more: the method is exact on this component of
  // this scene
  bool all_at_plateau = false;
};

// A point is on a plateau, left out of the fit, when its error is at most
// kFloorMultiple x the reference's floor (so every fitted error is at least
// that far above the reference) or kRoundingMultiple x the rounding level of
// its run (kRoundingPerStep x steps, steps = span / h).
inline constexpr double kFloorMultiple = 100.0;
inline constexpr double kRoundingMultiple = 10.0;
inline constexpr double kRoundingPerStep = 2.220446049250313e-16;  // one unit roundoff a step
// The asymptotic range starts where this many successive halving slopes
// agree within +- max(kHalvingAgreement, 0.05 p) of their mid-range p (the
// window's own rule for a point joining it).
inline constexpr int kHalvingSlopes = 3;
inline constexpr double kHalvingAgreement = 0.15;
// The halving slopes agree: within +- max(kHalvingAgreement, 0.05 p) of
// their mid-range p (false for none).
bool slopes_agree(const std::vector<double>& slopes);

// A verdict needs at least this many points in its window.
inline constexpr int kMinOrderPoints = 4;

// h and error are paired. Points with a non-finite error, or on a plateau
// (an error at most kFloorMultiple x floor or kRoundingMultiple x the
// rounding level kRoundingPerStep x span / h; span 0: no rounding level),
// are left out, and so is every point from the smallest h whose error passes ceiling
// upward (pre-asymptotic: a rotation angle or a length of the scene's unit
// size has nothing left to converge). No point is left out for its slope
// alone: an order lost at small steps far above the plateau is fitted. The
// window starts at the smallest steps, where the expansion in h holds best:
// it takes the kMinOrderPoints smallest steps, and a larger step joins it only while the local slope up to
// it stays within max(0.15, 0.05 p) of the window's slope p or, where the
// window's 95 % interval is wider than that (noisy errors), while the fit
// with it stays inside that interval; up to max_points (below
// kMinOrderPoints: that many, a slope without a verdict). So
// pre-asymptotic large steps, whose slope drifts, stay out, and a verdict
// rests on a slope its own interval does not contradict.
OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& error, double floor = 0.0,
                   double ceiling = 0.1, std::size_t max_points = 6, double span = 0.0);

// "exact" when every step's error lies on the plateau (all_at_plateau: no
// order to read, and none contradicted); otherwise
// "as declared" when the 95 % interval of the slope lies above declared -
// 0.2, "lower" when it lies below and the slope no longer climbs towards
// declared - 0.2 (climbing_to; inconclusive while it does), "inconclusive" when it is wider than
// +-0.3 or rests on fewer than kMinOrderPoints points; where the smallest
// steps are pre-asymptotic (pre_asymptotic) or the interval straddles
// declared - 0.2, "as declared" only where the plateau certifies it
// (certified_at_plateau), "inconclusive" otherwise.
std::string order_verdict(const OrderFit& fit, int declared);

// A ladder the plateau cut short (some point on the plateau: no finer step
// can add a halving) certifies but never condemns, in either of two forms:
// - halvings: its two smallest-step halving slopes are both at least bar,
//   the slope does not fall towards small steps (s0 >= s1 -
//   max(kHalvingAgreement, 0.05 s1)), and the window's interval lies above
//   bar;
// - rungs: the smallest step's rung slope is at least bar, and no rung slope
//   above it is higher by more than max(kHalvingAgreement, 0.05 x that
//   slope): the local slope is level or still climbing towards small steps.
//   High-order methods reach the plateau within one or two halvings, but
//   the quarter-step ladder gives them half-octave rungs.
// Either way the order is at least the declared one down to the plateau.
// A method that loses its order falls towards small steps; and slopes near
// the plateau flatten as the reference's error or rounding creeps in, so a
// low slope there is no evidence of a lower order.
bool certified_at_plateau(const OrderFit& fit, double bar);

// True when the local slope at the smallest steps still climbs towards
// bar: the smallest step's halving slope s0 reaches it, or would after one
// more halving at its last rise (s0 + (s0 - s1) >= bar). The halving
// slopes of rk4's omega on paraboloid-chaplygin, 3.82, 3.60, 3.63 from
// 2^-10 up, agree within +-0.19, and the window reads 3.63 +- 0.10 below
// 3.8; but at its smallest step the order is 3.82. A method that loses its
// order has slopes that fall towards small steps, far below the bar (the
// perturbed RK4: 1.0), and stays lower.
bool climbing_to(const OrderFit& fit, double bar);

// True when a fit with enough points has not shown its asymptotic range:
// fewer than kHalvingSlopes halving slopes above the plateau, or slopes
// that still move. A verdict either way waits for the asymptotic range: a
// method that lost its order at small steps reads its order at large ones,
// and a correct one reads low while its slopes still climb.
bool pre_asymptotic(const OrderFit& fit);

// True when a finer ladder could still decide: no point reached the
// plateau, and the fit is pre-asymptotic, its interval straddles
// declared - 0.2 (a slope still converging towards its order), its
// interval is too wide while its halving slopes still move (not
// asymptotic: the window spans a curve), or it has
// too few points because its ladder (kMinOrderPoints finite errors or
// more, the smallest step's among them) ends before the errors come under
// the ceiling.
bool wants_finer_steps(const OrderFit& fit, int declared);

// Why a verdict is inconclusive: "too few points" (below kMinOrderPoints in
// the window, or no fit), "floor" (as few, but only because points reached
// the plateau: a finer ladder at large h would give them), "failed runs"
// (as few because the ladder's other runs failed: fewer than
// kMinOrderPoints finite errors, on the plateau and above the ceiling
// included), "wide interval"
// (half-width above 0.3), "pre-asymptotic" (see pre_asymptotic, or an
// interval below declared - 0.2 whose slope still climbs towards it, see
// climbing_to; a finer ladder would decide), "no asymptotic range above the plateau"
// (pre-asymptotic, and the smallest steps reached the plateau) or
// "straddles" (the interval holds declared - 0.2); empty for a verdict.
std::string inconclusive_reason(const OrderFit& fit, int declared);

// The verdict on a component from its reference-based fit and its
// self-convergence fit (bench/lib/self_convergence.hpp): the reference
// fit's verdict, where the self-convergence slope confirms it (within
// +- max(kSelfAgreement, 0.05 declared) of the reference's slope);
// otherwise "inconclusive" with the reason: the reference fit's own, "no
// self-convergence" (no self slope) or "self-convergence disagrees".
inline constexpr double kSelfAgreement = 0.3;
struct OrderJudgement {
  std::string verdict, reason;  // reason empty for a verdict
};
OrderJudgement judge_order(const OrderFit& reference, const OrderFit& self, int declared);

}  // namespace rb

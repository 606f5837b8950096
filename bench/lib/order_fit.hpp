#pragma once
// Observed order of convergence: the least-squares slope of log(error)
// against log(h) over the asymptotic range, i.e. without the pre-asymptotic
// large steps and without the points that sit on a floor (rounding, or the
// reference's own error); its verdict against the declared order; and the
// straight-line fit that tolerance proportionality uses.
#include <limits>
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
  int at_floor = 0;  // measured points left out on the plateau (kFloorMultiple x plateau_level)
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
  // the trend test (trend_of): the halving slopes from the smallest step
  // kept up, kTrendSlopes at most (halving_slopes are the first of them),
  // and the least-squares change of the slope per halving towards small
  // steps (negative: the slope falls as h falls) with the half-width of its
  // 95 % interval; NaN below 3 slopes
  std::vector<double> trend_slopes;
  double trend = std::numeric_limits<double>::quiet_NaN();
  double trend_ci95 = std::numeric_limits<double>::quiet_NaN();
  // every step's error is on the plateau (runs that failed have none), at
  // kMinOrderPoints steps or more: the method is exact on this component of
  // this scene
  bool all_at_plateau = false;
};

// A point is on the plateau, left out of the fit, when its error is at most
// kFloorMultiple x the plateau level of its step (plateau_level): so every
// fitted error lies at least that far above the reference's own error and
// above the rounding of its own run, as the reference measured it.
inline constexpr double kFloorMultiple = 100.0;
// The plateau level at step h: the floor (the reference's own error, the
// disagreement of two solutions in double precision, rounding included)
// where the run takes no more steps than the reference's finer solution
// (rounding_step, its step), and where it takes more, the floor scaled by
// the ratio of the steps, rounding_step / h: a run's rounding grows at most
// linearly with its steps (rk4 on valley-sideways errs 4e-14 at 2^-11 and
// 7e-13 at 2^-17, 64 times the steps). rounding_step 0: the floor alone.
double plateau_level(double floor, double rounding_step, double h);
// The asymptotic range starts where this many successive halving slopes
// agree within +- max(kHalvingAgreement, 0.05 p) of their mid-range p (the
// window's own rule for a point joining it).
inline constexpr int kHalvingSlopes = 3;
inline constexpr double kHalvingAgreement = 0.15;
// The halving slopes agree: within +- max(kHalvingAgreement, 0.05 p) of
// their mid-range p (false for none).
bool slopes_agree(const std::vector<double>& slopes);

// The trend test reads up to this many halving slopes from the smallest
// step kept up (3 at least: a line through 2 has no interval).
inline constexpr int kTrendSlopes = 5;

// The least-squares line of the slopes (from the smallest step up) against
// the halving index towards small steps: its slope, the change of the
// slope per halving (negative: falling as h falls), and the half-width of
// its 95 % interval; NaN for both below 3 slopes.
LineFit trend_of(const std::vector<double>& slopes);

// True when the slope falls away from the declared order towards small
// steps, so that more halvings may still take it out of the band (the
// verdict waits: "pre-asymptotic"): the trend (OrderFit::trend) lies
// below 0 by more than 0.005 a halving over all of its 95 % interval, and
// the slopes do not settle onto the declared order from above. Settling:
// the smallest step's slope at least the declared order (0.02 less where
// the plateau ends the ladder: what the reference 100 x below can take off
// the last halving), the last fall no larger than the one before it, and
// the falls still to come, shrinking at that ratio, leaving it within 0.05
// of the declared order: so an expansion C h^p (1 + D h + ...) converges,
// its slope never crossing p once D h is small (rk4's contact on
// valley-sideways reads 4.003, 4.005, 4.010 from 2^-10 up). A method that
// lost its order has slopes that fall ever faster: the RK4 with a42 = 1e-3
// reads 3.94, 3.88, 3.79 on valley-sideways down to 2^-9, and 3.64, 3.48
// below. Slopes still falling by 0.15 a halving where the plateau ends the
// ladder (rk4 on chaplygin-bumpy-long: 4.87, 4.78, 4.64, 4.48, 4.32) have
// no asymptotic range above it.
bool falling(const OrderFit& fit, int declared);

// True when the last slopes lie inside the band: the smallest step's local
// slope (its rung slope, over half an octave where the ladder has one,
// else its halving slope) at least bar (none: the window alone decides),
// and where more halvings can run (no point on the plateau) that slope
// less its last fall too: carried on for one more step, the fall stays in
// the band.
// A slope that rose into the band is in it: a rise cannot turn a pass
// into lower, only a fall can (a rise stops a lower verdict, climbing_to).
bool slopes_in_band(const OrderFit& fit, double bar);

// A verdict needs at least this many points in its window.
inline constexpr int kMinOrderPoints = 4;

// h and error are paired. Points with a non-finite error, or on the plateau
// (an error at most kFloorMultiple x plateau_level(floor, rounding_step,
// h)), are left out, and so is every point from the smallest h whose error passes ceiling
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
                   double ceiling = 0.1, std::size_t max_points = 6, double rounding_step = 0.0);

// "exact" when every step's error lies on the plateau (all_at_plateau: no
// order to read, and none contradicted); "inconclusive" below
// kMinOrderPoints points; "as declared" only where the last slopes lie
// inside the band (slopes_in_band) and the slope does not fall away from
// the declared order (falling: more halvings may take it out of the band),
// and then when the halving slopes agree (asymptotic) and the 95 %
// interval of the slope lies above declared - 0.2, or where the plateau
// certifies it (certified_at_plateau; an interval wider than +-0.3 only
// where all of it lies above declared - 0.2); "lower" when the interval, at most +-0.3 wide,
// lies below declared - 0.2, the halvings agree and the slope no longer
// climbs towards declared - 0.2 (climbing_to); "inconclusive" otherwise.
// So more halvings do not turn one verdict into the other: a pass needs
// slopes that do not fall, a lower verdict slopes that do not climb.
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
// A fall beyond the agreement certifies only where the slopes settle onto
// the declared order from above (as falling reads it, none of three below
// declared - 0.02: rkmk8's rotation on valley-sideways, rungs 8.16, 8.33,
// 8.78 from the smallest step up, falls 0.17 after 0.45).
//   High-order methods reach the plateau within one or two halvings, but
//   the quarter-step ladder gives them half-octave rungs.
// Either way the order is at least the declared one down to the plateau.
// A method that loses its order falls towards small steps; and slopes near
// the plateau flatten as the reference's error or rounding creeps in, so a
// low slope there is no evidence of a lower order.
bool certified_at_plateau(const OrderFit& fit, double bar);

// True when the local slope at the smallest steps still climbs towards
// bar: the smallest step's halving slope s0 reaches it, or would after one
// more halving at its last rise (s0 + (s0 - s1) >= bar) or at the upper end
// of the trend's interval (s0 + trend + trend_ci95 >= bar, trend above 0:
// a correct method's slope approaches its order with rises that shrink, so
// no further rise exceeds the last one or the trend's). The halving
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
// (half-width above 0.3, not above declared - 0.2), "pre-asymptotic" (see
// pre_asymptotic; or the slope falls away from the declared order, see
// falling, or the last slopes lie outside the band while the window lies
// above it; or an interval below declared - 0.2 whose slope still climbs
// towards it, see climbing_to: a finer ladder would decide), "no asymptotic range above the plateau"
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

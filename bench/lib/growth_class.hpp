#pragma once
// The growth class of an error series over a long run: bounded, linear,
// quadratic, another power of t, exponential, at rounding, or undecided
// (docs/usage.md#the-horizon-study). The series is an envelope: the largest
// error in each of a few windows a decade of t (windowed_maximum), as
// GeometricProblems.jl's compute_error_drift takes it, so that a late
// window does not carry an early peak and an oscillation's troughs do not
// read as growth. A class needs `decades` decades of t (three) whose slopes
// agree: a law still changing (slopes climbing 0.24, 0.49, 0.63, 0.77 a
// decade, or a growth that saturates in the last decade) is "undecided",
// never the class its early decades suggest. The horizon study fits every
// series it records with classify_growth; any other long-run study can
// (it takes t and the error, nothing of the study).
#include <string>
#include <utility>
#include <vector>

#include "bench/lib/sweep.hpp"

namespace rb {

enum class GrowthClass { none, undecided, rounding, bounded, linear, quadratic, power, exponential };

// "undecided", "rounding", "bounded", "linear", "quadratic", "power",
// "exponential"; "none" for none (no fit: the report writes null).
const char* growth_class_name(GrowthClass c);

// decided: a class other than none and undecided.
bool decided(GrowthClass c);

// What decides a class (HorizonSpec carries the study's).
struct GrowthRules {
  // the window: the last `decades` decades of t, t_to 10^-decades .. t_to;
  // fewer decades of data: undecided
  int decades = 3;
  // no drift: the window's per-decade slopes span at most this
  double spread = 0.15;
  // the last decade's slope lies within the 95 % interval of the fit over
  // the window's earlier decades (their half-widths combined), or within
  // this of it where that interval is narrower: slopes are read to 0.05
  double resolution = 0.05;
  // the classes' bands of p: bounded p <= band, linear |p - 1| <= band,
  // quadratic |p - 2| <= band, power between them; every decade of the
  // window must lie in its class's band over its whole 95 % interval
  double band = 0.25;
  // exponential: the window's slopes rising, the last at least this and
  // 1.5 times the one before (e^(lambda t) has slope lambda t on log-log:
  // ten times larger a decade on; a power law keeps one slope)
  double exponential_slope = 3.0;
};

// The slope of log10 err on log10 t over one decade of t.
struct DecadeSlope {
  double t_from = 0.0, t_to = 0.0;
  double p = kNaN, ci95 = kNaN;  // NaN below kMinGrowthPoints values > 0
  int points = 0;                // values > 0 in the decade, both ends in
};

// Growth samples need this many points in a decade (and in the window) for a fit.
inline constexpr int kMinGrowthPoints = 4;

// err ~ C t^p over the window [t_from, t_to], and its class.
struct GrowthFit {
  double p = kNaN;     // slope of log10 err on log10 t over the window; NaN without a fit
  double ci95 = kNaN;  // half-width of its 95 % interval (points taken as independent)
  double log10_c = kNaN;
  double t_from = 0.0, t_to = 0.0;
  int points = 0;         // values > 0 in the window
  double largest = kNaN;  // the largest value in the window
  double rounding_level = 0.0;
  bool at_rounding = false;  // largest <= rounding_level: the series is rounding, not the method
  // every whole decade back from t_to that the samples cover, oldest
  // first: the window's are the last rules.decades of them
  std::vector<DecadeSlope> decades;
  double p_earlier = kNaN, ci95_earlier = kNaN;  // the window but its last decade
  double p_last = kNaN, ci95_last = kNaN;        // the last decade
  GrowthClass growth_class = GrowthClass::none;
  // why this class, or why undecided, or why no fit (class none)
  std::string reason;
};

// The class of the pairs (t, err), t > 0 rising (the windows' ends), err
// >= 0 or NaN (no value): the window and the decades end at the last t.
// rounding: the level at or below which the series is rounding.
GrowthFit classify_growth(const std::vector<double>& t, const std::vector<double>& err, double rounding,
                          const GrowthRules& rules = {});

// The envelope of a densely sampled series: for window ends at
// 10^(k / per_decade) times t.front() (and t.back()), the largest finite
// err over (previous end, end]; NaN where a window holds none. first: the
// window ends; second: the maxima.
std::pair<std::vector<double>, std::vector<double>> windowed_maximum(const std::vector<double>& t,
                                                                     const std::vector<double>& err, int per_decade);

}  // namespace rb

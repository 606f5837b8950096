#pragma once
// The long-horizon study (docs/usage.md#the-horizon-study): per scene and
// fixed-step method one run of HorizonSpec::steps steps of h, its energy
// error |H - H0| and rotation defect ||R^T R - I||_F recorded as their
// envelope over log-spaced windows (the largest in each window), and for
// each the growth exponent p of err ~ C t^p, fitted by least squares on
// log-log over the run's later part; the fit says whether its early and
// late halves agree (asymptotic), and series identical to another run's
// (the same tableau on (v, alpha) of a homogeneous ball) are marked.
// Where the stability study asks "does it stay bounded", this asks "how fast
// does it grow": t^0 bounded, t^1 a steady drift, t^2 a drift that feeds on
// itself, t^(1/2) a random walk of rounding errors.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/lib/sweep.hpp"

namespace rb {

// err ~ C t^p over [t_from, t_to].
struct GrowthFit {
  double p = kNaN;     // slope of log10 err on log10 t; NaN without a fit
  double ci95 = kNaN;  // half-width of its 95 % interval (least squares, points taken as independent)
  // the slopes over the first and the second half of the window (in log t):
  // where they differ by more than ci95 the growth law is still changing,
  // a wider and more honest interval than ci95
  double p_early = kNaN, p_late = kNaN;
  double log10_c = kNaN;  // intercept: log10 C
  double t_from = 0.0, t_to = 0.0;
  int points = 0;         // samples in the window with a finite value > 0
  double largest = kNaN;  // the largest value in the window
  double rounding_level = 0.0;
  bool at_rounding = false;  // largest <= rounding_level: p describes rounding, not the method
  bool asymptotic = false;   // |p_late - p_early| <= HorizonSpec::asymptotic_spread (false without a fit)
  std::string why_none;      // why p is NaN (empty when there is a fit)
};

// Growth samples need this many points in the window for a fit.
inline constexpr int kMinGrowthPoints = 4;

// The fit of the pairs (t, err) with t in [t_from, t_to] and err finite and
// > 0; t and err are paired.
GrowthFit fit_growth(const std::vector<double>& t, const std::vector<double>& err, double t_from, double t_to,
                     double rounding_level);

// The error of one first integral of the scene (InvariantMeter: relative to
// its magnitude at the start), recorded and fitted like the energy error.
struct InvariantSeries {
  std::string name;  // "routh-paraboloid.J1"
  std::vector<double> error;
  GrowthFit fit;
};

struct HorizonRecord {
  std::size_t index = 0;  // position in the full (unsharded) study
  std::string scene;
  bool r_feeds_back = false;
  MethodInfo method;
  long coarsening = 1;  // 1: the study's run; k: a price run of steps / k steps of k h
  double h = 0.0;
  long steps = 0;  // planned; the run ends at t_end = steps h
  double t_end = 0.0;
  Status status = Status::ok;
  std::string message;
  double stop_time = 0.0;
  Cost cost;
  double wall_s = 0.0;        // the integration and the measurement
  double cpu_s = 0.0;         // the same, in this run's thread's CPU time (its price: runs share threads)
  double energy_scale = 0.0;  // m g0 r + the starting kinetic energy (J)
  // at the sample times: the envelope, the largest of the states measured
  // (the samples and a uniform grid of about dense_outputs states between)
  // in the window (the previous sample time, t]; NaN where none is finite
  std::vector<double> t, energy_error, rotation_defect;
  GrowthFit energy_fit, defect_fit;
  // the scene's declared first integrals, in InvariantMeter's order
  std::vector<InvariantSeries> invariants;
};

struct HorizonResults {
  std::vector<HorizonRecord> runs;
};

// Two series of one scene are the same to rounding when they are recorded
// at the same times, no sample differs by more than their rounding level
// (the larger of the two fits' rounding_level), and they rise above
// kSameSeriesRise times it (two series at rounding are not "the same").
// rk4, rkmk4, cf4 and rk4-projected's energy errors on a homogeneous ball
// (one tableau on (v, alpha)) differ by ~1e-13 J over 10^6 steps, against a
// level of ~1e-11 J.
inline constexpr double kSameSeriesRise = 100.0;

// Marks, in the report's horizon runs, every series that is the same as
// that of an earlier run (by index) of its scene:
// "same_as": {"energy_error": name or null, "rotation_defect": name or
// null, "invariants": {integral: name or null}}, the name of the first such
// run. The sweep and the merge both call it.
void mark_same_series(nlohmann::json& runs);

// The sample step counts: round(10^(k / per_decade)) for k = 0, 1, ...,
// without repeats, below steps, then steps itself.
std::vector<long> horizon_sample_steps(long steps, int per_decade);

// The rounding level of a series after n steps: 100 eps sqrt(n) (a random
// walk of rounding errors) times the series' scale.
double rounding_level(long steps, double scale);

// One run of the study: never throws for a failing method (a failure is its
// status, its samples up to the stop and no fit).
HorizonRecord horizon_run(const Problem& problem, const Integrator& method, const HorizonSpec& spec);

// Checks the spec: every integrator known and fixed-step, steps, h and the
// sampling in range; throws InputError naming the option.
void check_horizon(const HorizonSpec& spec);

// --horizon-steps TEXT: a whole number from 1000 to 1e8 ("100000", "1e6");
// throws InputError (key "horizon-steps") otherwise.
long parse_horizon_steps(const std::string& text);

// The coarsenings k of HorizonSpec::coarsenings that give price runs: those
// above 1 that divide steps, without repeats, in the given order.
std::vector<long> price_coarsenings(const HorizonSpec& spec);

// This shard's runs (index % count == shard index), scenes outer, methods
// inner, in that order, the study's runs first and then each coarsening's
// price runs in the same order, computed on spec.jobs threads; progress gets
// a line per run, as each ends.
HorizonResults run_horizon(const SweepSpec& spec, const std::function<void(const std::string&)>& progress);

// The report's "horizon" section (docs/formats.md#the-horizon-study).
nlohmann::json horizon_json(const HorizonResults& results);

// Its options, in the report's "options" (so that shards of different
// studies do not merge).
nlohmann::json horizon_options_json(const HorizonSpec& spec);

}  // namespace rb

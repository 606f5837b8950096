#pragma once
// The long-horizon study (docs/usage.md#the-horizon-study): per scene and
// fixed-step method one run of HorizonSpec::steps steps of h, its energy
// error |H - H0| and rotation defect ||R^T R - I||_F recorded as their
// envelope over log-spaced windows (the largest in each window), and for
// each its growth class (bench/lib/growth_class.hpp: bounded, linear, ...,
// or undecided) from the exponent p of err ~ C t^p over the run's last
// three decades, each decade confirming it; where a class is undecided the
// study runs the next decade (10 times the steps) while its budget allows
// (HorizonSpec::steps_max, cpu_max_s). Series identical to another run's
// (the same tableau on (v, alpha) of a homogeneous ball) are marked.
// Where the stability study asks "does it stay bounded", this asks "how fast
// does it grow": t^0 bounded, t^1 a steady drift, t^2 a drift that feeds on
// itself, t^(1/2) a random walk of rounding errors.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/lib/growth_class.hpp"
#include "bench/lib/sweep.hpp"
#include "problems/invariants.hpp"

namespace rb {

// The error of one first integral of the scene (InvariantMeter: relative to
// its magnitude at the start), recorded and fitted like the energy error.
struct InvariantSeries {
  std::string name;                             // "routh-paraboloid.J1"
  IntegralKind kind = IntegralKind::dynamical;  // kinematic: kept by any method, no evidence of structure
  std::vector<double> error;
  GrowthFit fit;
};

// A shorter run of the study's scene and method, made before the record's
// own: its class was undecided and the budget allowed the next decade.
struct EarlierRun {
  long steps = 0;
  double t_end = 0.0;
  Status status = Status::ok;
  double cpu_s = 0.0, wall_s = 0.0;
  // the largest value of each series over the whole run (the price of
  // staying under a target over the study's first horizon reads them)
  double energy_error = kNaN, energy_error_on_group = kNaN, rotation_defect = kNaN;
  GrowthClass energy_class = GrowthClass::none, energy_on_group_class = GrowthClass::none,
              defect_class = GrowthClass::none;
};

struct HorizonRecord {
  std::size_t index = 0;  // position in the full (unsharded) study
  std::string scene;
  bool r_feeds_back = false;
  MethodInfo method;
  long coarsening = 1;  // 1: the study's run; k: a price run of steps / k steps of k h
  double h = 0.0;
  long steps = 0;  // planned; the run ends at t_end = steps h
  // the steps the study asked for (HorizonSpec::steps, or steps / k for a
  // price run): steps is 10^j times it where the class was undecided
  long study_steps = 0;
  std::vector<EarlierRun> earlier;  // the shorter runs before this one, shortest first
  // a series the study classes is undecided and the next decade was past
  // the budget: why (empty otherwise)
  std::string budget_reason;
  double t_end = 0.0;
  Status status = Status::ok;
  std::string message;
  double stop_time = 0.0;
  Cost cost;
  double wall_s = 0.0;        // the integration and the measurement
  double cpu_s = 0.0;         // the same, in this run's thread's CPU time (its price: runs share threads)
  double energy_scale = 0.0;  // m g0 r + the starting kinetic energy (J)
  // at the sample times: the envelope, the largest of the states measured
  // (the samples, a uniform grid of about dense_outputs states between and
  // window_outputs states evenly spaced in each window) in the window (the
  // previous sample time, t]; NaN where none is finite
  std::vector<double> t, energy_error, rotation_defect;
  GrowthFit energy_fit, defect_fit;
  // the energy error at the nearest rotation, |H(polar(R), v, alpha) - H0|
  // (bench/lib/drift.hpp), at the same samples, and its fit: what the
  // findings read (the flat H hides R's drift off SO(3))
  std::vector<double> energy_error_on_group;
  GrowthFit energy_on_group_fit;
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

// The series whose class decides whether the study runs the next decade:
// the energy error, flat and at the nearest rotation, and the rotation defect.
bool any_undecided(const HorizonRecord& r);

// The study's run of one scene and method, decade by decade: horizon_run
// at spec.steps, then, while any_undecided and the next decade's run (10
// times the steps) stays within spec.steps_max and its CPU time, predicted
// as 10 times this run's, within spec.cpu_max_s, again at 10 times the
// steps. The record is the last run, with the earlier ones in `earlier` and
// the budget's reason where it stopped an undecided class.
HorizonRecord horizon_decades(const Problem& problem, const Integrator& method, const HorizonSpec& spec);

// Checks the spec: every integrator known and fixed-step, steps, h and the
// sampling in range; throws InputError naming the option.
void check_horizon(const HorizonSpec& spec);

// --horizon-steps TEXT: a whole number from 1000 to 1e8 ("100000", "1e6");
// throws InputError (key "horizon-steps", or the key given) otherwise.
long parse_horizon_steps(const std::string& text, const std::string& key = "horizon-steps");

// --horizon-cpu-max TEXT: seconds, a finite number > 0; throws InputError
// (key "horizon-cpu-max") otherwise.
double parse_horizon_cpu_max(const std::string& text);

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

#pragma once
// What a sweep runs: scenes x integrators x step sizes or tolerances, and the
// named presets (quick for CI, default for the README's main job, full for a
// study, regime for the regime map). All defaults of the runner live here.
#include <optional>
#include <string>
#include <vector>

#include "bench/lib/regime_grid.hpp"
#include "integrators/controllers/controller.hpp"

namespace rb {

// What the stability study reads off a run (bench/lib/stability_verdict.hpp):
// the drift bounds, whose crossing limits the step at a horizon, and the
// blow-up rules, which no bounded motion meets at any horizon.
struct StabilityBounds {
  // drift bounds: the drift-limited step h*(T) is the largest whose run to
  // T keeps max |H - H0| / energy scale (H at the nearest rotation,
  // problems/energy.hpp) and max ||R^T R - I||_F within these. A
  // non-symplectic method's energy error and a flat method's defect grow
  // as a power of t at any h, so h*(T) falls as T grows: that is what it
  // measures. At 0.1, cf4 at h = 1 on bumpy-long (45 % off at 10 s) is
  // outside it
  double energy_fraction = 0.1;
  double rotation_defect = 0.5;  // R is no rotation any more
  // blow-up bounds, where no bounded motion goes: the energy error ten
  // times the energy scale, and a defect past 10 (a flat method's update
  // of R is linear in R: R shrinks, the defect then tends to sqrt(3), or
  // it grows geometrically)
  double blow_up_energy = 10.0;
  double blow_up_defect = 10.0;
  // a failure counts as a blow-up where it comes before the run leaves its
  // drift bounds or within this many steps of it: from the drift bound to
  // the blow-up bound within 10 steps is an error multiplied by at least
  // 20^(1/10) = 1.35 a step, the step's own instability; a run that drifts
  // out first and fails later (its energy drifted until the ball left the
  // scene) fails of its drift, and the horizon it takes moves with the step
  int blow_up_steps = 10;
  // the growth shape each rung reports beside its verdict (not read by it):
  // exponential where over the run's last doubling of time the envelope
  // grows as t^p with p >= growth_exponent, over the doubling before as
  // t^p' with p' >= growth_exponent / 3, and p >= 1.5 p' (accelerating:
  // e^(lambda t) has p = 2 p'; a power law has p = p')
  double growth_exponent = 3.0;
  // series whose last window stays below it are not called exponential
  // (relative energy, defect): a series at rounding jumps by any factor
  double growth_floor = 1e-9;
};

// The largest horizon --stability-horizons takes (s): 10^9 steps of the
// ladder's smallest 2^-10 s
inline constexpr double kMaxStabilityHorizon = 1e6;

struct StabilitySpec {
  bool enabled = false;
  std::vector<std::string> scenes;       // bounded scenes for long runs
  std::vector<std::string> integrators;  // methods for the long drift runs
  double drift_h = 0.01;                 // step of the long runs
  double drift_t_end = 1000.0;           // 10^5 steps at h = 0.01
  int drift_samples = 40;                // log-spaced output times
  // the ladder h = h_max, h_max / 2, ... down to h_min, each rung one run
  // to the last horizon (whatever the scene's own t_end), judged at every
  // horizon on its way; downward until a rung keeps every drift bound to
  // the last horizon (a smaller step is not run)
  double search_h_min = 1.0 / 1024.0;
  double search_h_max = 8.0;
  // the horizons T of the drift-limited step h*(T), increasing
  // (--stability-horizons); the blow-up step is read at each too
  std::vector<double> horizons = {10.0, 100.0, 1000.0};
  int search_outputs = 512;  // states recorded per horizon's stretch of a rung (whole steps, evenly spaced)
  StabilityBounds bounds;
};

// "10,100,1000" -> the stability study's horizons: positive finite
// numbers up to kMaxStabilityHorizon, increasing; throws InputError
// naming key (parse_number_list's rules, then these).
std::vector<double> parse_stability_horizons(const std::string& text, const std::string& key);

// The long-horizon study (bench/lib/horizon.hpp, docs/usage.md#the-horizon-study):
// steps fixed steps of h on each scene, the energy error and the rotation
// defect as their envelope over log-spaced windows, and their growth class
// (bench/lib/growth_class.hpp) over the last fit_decades decades of t; an
// undecided class runs the next decade while the budget allows.
struct HorizonSpec {
  bool enabled = false;
  std::vector<std::string> scenes;       // one homogeneous, one where R feeds back
  std::vector<std::string> integrators;  // fixed-step methods
  double h = 1.0 / 128.0;                // a power of two: every sample time n h is exact
  long steps = 1'000'000;
  // the budget of the decades after the first (--horizon-steps-max,
  // --horizon-cpu-max): a run whose class is undecided runs again at 10
  // times the steps while they stay within steps_max (0: steps, so no
  // further decade) and its CPU time, predicted as 10 times the last run's,
  // within cpu_max_s
  long steps_max = 0;
  double cpu_max_s = 600.0;
  int samples_per_decade = 8;   // log-spaced sample times (in steps): the windows' ends
  int fit_decades = 3;          // class window: t_end 10^-fit_decades .. t_end (GrowthRules::decades)
  long dense_outputs = 20'000;  // states measured between samples for the envelope
  long window_outputs = 64;     // and at least this many evenly spaced in each window
  // no drift: the window's per-decade slopes span at most this
  // (GrowthRules::spread)
  double asymptotic_spread = 0.15;
  // the price runs: each scene and method again over the same horizon in
  // steps / k steps of k h, for each k here that divides steps, so that the
  // cost of staying under an energy target is read off more than one step
  // (a method that stays under at h may stay under at 4 h for a quarter of
  // the price); no exponent is read from them
  std::vector<long> coarsenings = {4, 16};
};

struct SweepSpec {
  std::string preset = "custom";
  std::vector<std::string> scenes;  // shipped names or JSON paths; empty: all shipped
  // the regime study: scenes generated from this grid instead of scenes
  // (bench/lib/regime_scenes.hpp)
  std::optional<RegimeGrid> regime;
  std::vector<std::string> integrators;  // registry names; empty: all registered
  std::vector<double> hs;                // step sizes of fixed-step methods
  std::vector<double> tols;              // rtol = atol of adaptive methods
  double t_end = 0.0;                    // 0: each scene's own t_end
  // spacing of the outputs the timed call records (rollbench run --dt-out);
  // 0: t_end only, so that no method's steps are set by outputs the
  // comparison does not need
  double dt_out = 0.0;
  // spacing of the grid error_max and the drift are measured on (untimed);
  // --dt-out replaces it
  double error_dt = 0.25;
  int repeats = 3;                       // timed repeats per run (serial, one thread)
  double repeat_budget_s = 1.0;          // stop repeating a run once its samples took this long
  int jobs = 2;                          // threads for the accuracy runs
  int shard_index = 0, shard_count = 1;  // this process runs the runs with index % count == index
  long max_steps = 5'000'000;
  // halve the smallest step of a fixed-step method whose order fit is still
  // pre-asymptotic, round after round (bench/lib/finer_steps.hpp); an
  // unsharded sweep only: a shard does not see its method's other runs
  bool extend_ladders = true;
  // the step-size controller of the adaptive methods that take one (a
  // filter: i, pi, pid; RunOptions::controller); nullptr: each method's own
  const ControllerKind* controller = nullptr;
  StabilitySpec stability;
  HorizonSpec horizon;
  std::string cache_dir;  // reference cache; empty: none
};

// The named preset; throws InputError (key "preset") for an unknown name.
SweepSpec preset(const std::string& name);

// "1e-3,1e-4" or "2^-3..2^-8" (powers of two, inclusive) -> numbers; throws
// InputError naming the key on bad text.
std::vector<double> parse_number_list(const std::string& text, const std::string& key);

}  // namespace rb

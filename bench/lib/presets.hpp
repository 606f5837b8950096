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

// What fails a rung of the stability study (bench/lib/stability_verdict.hpp):
// a failure, never an accuracy threshold.
struct StabilityBounds {
  // max |H - H0| / energy scale above it fails: the energy error as large
  // as the energy itself. A smaller fraction is an accuracy threshold that
  // a non-symplectic method's drift (linear in t at any h) passes at some
  // horizon: at 0.1 rkmk3, cf4 and others lost two ladder steps from a 10 s
  // to a 40 s horizon, at 1 none of order >= 2 did
  double energy_fraction = 1.0;
  double rotation_defect = 0.5;  // max ||R^T R - I||_F above it fails: R is no rotation any more
  // exponential growth: over the run's last doubling of time the envelope
  // grows as t^p with p >= growth_exponent, over the doubling before as
  // t^p' with p' >= growth_exponent / 3, and p >= 1.5 p' (accelerating:
  // e^(lambda t) has p = 2 p'; a power law has p = p')
  double growth_exponent = 3.0;
  // series whose last window stays below it are not judged for growth
  // (relative energy, defect): a series at rounding jumps by any factor
  double growth_floor = 1e-9;
};

struct StabilitySpec {
  bool enabled = false;
  std::vector<std::string> scenes;       // bounded scenes for long runs
  std::vector<std::string> integrators;  // methods for the long drift runs
  double drift_h = 0.01;                 // step of the long runs
  double drift_t_end = 1000.0;           // 10^5 steps at h = 0.01
  int drift_samples = 40;                // log-spaced output times
  // largest stable step: h = h_min, 2 h_min, ... up to the first that fails
  // (StabilityBounds) or h_max, each run to exactly search_t_end whatever
  // the scene's own t_end
  double search_h_min = 1.0 / 1024.0;
  double search_h_max = 8.0;
  double search_t_end = 10.0;
  int search_outputs = 512;  // states recorded per rung (whole steps, evenly spaced)
  StabilityBounds bounds;
};

// The long-horizon study (bench/lib/horizon.hpp, docs/usage.md#the-horizon-study):
// steps fixed steps of h on each scene, the energy error and the rotation
// defect as their envelope over log-spaced windows, and the growth exponent
// p of err ~ C t^p fitted over the last fit_decades decades of t.
struct HorizonSpec {
  bool enabled = false;
  std::vector<std::string> scenes;       // one homogeneous, one where R feeds back
  std::vector<std::string> integrators;  // fixed-step methods
  double h = 1.0 / 128.0;                // a power of two: every sample time n h is exact
  long steps = 1'000'000;
  int samples_per_decade = 8;   // log-spaced sample times (in steps)
  double fit_decades = 2.0;     // fit window: t_end 10^-fit_decades .. t_end
  long dense_outputs = 20'000;  // states measured between samples for the envelope
  // the fit is asymptotic where its early and late half-window slopes
  // differ by at most this
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

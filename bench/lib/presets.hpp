#pragma once
// What a sweep runs: scenes x integrators x step sizes or tolerances, and the
// named presets (quick for CI, default for the README's main job, full for a
// study, regime for the regime map). All defaults of the runner live here.
#include <optional>
#include <string>
#include <vector>

#include "bench/lib/regime_grid.hpp"

namespace rb {

struct StabilitySpec {
  bool enabled = false;
  std::vector<std::string> scenes;       // bounded scenes for long runs
  std::vector<std::string> integrators;  // methods for the long drift runs
  double drift_h = 0.01;                 // step of the long runs
  double drift_t_end = 1000.0;           // 10^5 steps at h = 0.01
  int drift_samples = 40;                // log-spaced output times
  // largest stable step: h = h_min, 2 h_min, ... up to the first that fails
  // or h_max; stable: the run reaches t_end (finite, model valid) with
  // max |H - H0| <= energy_fraction * (m g0 r + the starting kinetic energy)
  // and max ||R^T R - I||_F < rotation_defect_bound over the run: the whole
  // state bounded, not the energy alone
  double search_h_min = 1.0 / 1024.0;
  double search_h_max = 8.0;
  double search_t_end = 10.0;
  double energy_fraction = 0.1;
  double rotation_defect_bound = 1e-2;
};

// The long-horizon study (bench/lib/horizon.hpp, docs/usage.md#the-horizon-study):
// steps fixed steps of h on each scene, the energy error and the rotation
// defect as their largest so far at log-spaced times, and the growth exponent
// p of err ~ C t^p fitted over the last fit_decades decades of t.
struct HorizonSpec {
  bool enabled = false;
  std::vector<std::string> scenes;       // one homogeneous, one where R feeds back
  std::vector<std::string> integrators;  // fixed-step methods
  double h = 1.0 / 128.0;                // a power of two: every sample time n h is exact
  long steps = 100'000;
  int samples_per_decade = 8;   // log-spaced sample times (in steps)
  double fit_decades = 2.0;     // fit window: t_end 10^-fit_decades .. t_end
  long dense_outputs = 20'000;  // states measured between samples for the largest-so-far
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
  // the step-size controller of the adaptive methods that take one (i, pi,
  // pid; RunOptions::controller); empty: each method's own
  std::string controller;
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

#pragma once
// Where methods fail: long runs whose energy error and rotation defect are
// recorded at log-spaced times (bounded, linear, quadratic growth or blow-up
// can be read off), and for each fixed-step method the largest step below
// which every step of the study runs to the study's horizon without failing
// (bench/lib/stability_verdict.hpp: it stops, its energy error passes a
// fraction of the energy scale, R leaves SO(3) by O(1), or either grows
// exponentially). Accuracy is not stability: the energy error and the
// rotation defect at h are reported beside the verdict, not used for it.
#include <string>
#include <vector>

#include "bench/lib/stability_verdict.hpp"
#include "bench/lib/sweep.hpp"

namespace rb {

struct DriftRecord {
  std::size_t index = 0;  // position in the full (unsharded) list
  std::string scene;
  MethodInfo method;
  double h = 0.0;
  Status status = Status::ok;
  std::string message;
  double stop_time = 0.0;
  std::vector<double> t, energy_error, rotation_defect;
  Cost cost;
  double wall_s = 0.0;
};

struct StableStepTry {
  double h;
  Status status;
  std::string message;     // the run's, where it stopped
  double stop_time;        // the horizon, or where it stopped
  double energy_error;     // max |H - H0| / the energy scale over the recorded states (up to a stop)
  double rotation_defect;  // max ||R^T R - I||_F over them
  GrowthShape energy_growth, defect_growth;
  StabilityFailure failure;  // none: stable
  bool stable;
};

// The largest h of the ladder h_min, 2 h_min, ... at which the run and every
// run at a smaller h of the ladder were stable, each run to t = horizon.
struct StableStepRecord {
  std::size_t index = 0;
  std::string scene;
  MethodInfo method;
  double h = kNaN;             // NaN when even h_min was not stable
  double horizon = 0.0;        // every rung runs to it (StabilitySpec::search_t_end)
  double energy_scale = 0.0;   // m g0 r + the starting kinetic energy
  StabilityBounds bounds;      // what fails a rung
  double energy_error = kNaN;  // at h: accuracy beside the verdict
  double rotation_defect = kNaN;
  bool at_limit = false;             // h is the ladder's top: the method may be stable beyond
  std::vector<StableStepTry> tried;  // by h ascending, up to the first unstable one
};

struct StabilityResults {
  std::vector<DriftRecord> drift;
  std::vector<StableStepRecord> largest_stable_h;
};

// Runs this shard's part of the stability study (tasks with index % count ==
// shard index). progress gets a line now and then.
StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress);

}  // namespace rb

#pragma once
// Where methods fail: long runs whose energy error and rotation defect are
// recorded at log-spaced times (bounded, linear, quadratic growth or blow-up
// can be read off), and for each fixed-step method the largest step at which
// it stays finite and within stated error thresholds.
#include <string>
#include <vector>

#include "bench/lib/sweep.hpp"

namespace rb {

struct DriftRecord {
  std::size_t index = 0;  // position in the full (unsharded) list
  std::string scene, integrator, family;
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
  double contact_error;  // NaN when the run failed
  double energy_error;   // max |H - H0| over the run, in units of m g0 r
  double rotation_defect;  // max ||R^T R - I||_F over the run
};

struct StableStepRecord {
  std::size_t index = 0;
  std::string scene, integrator, family;
  double h = kNaN;  // the largest stable step; NaN when none was found
  double contact_threshold = 0.0, energy_threshold = 0.0, rotation_threshold = 0.0;
  std::vector<StableStepTry> tried;
};

struct StabilityResults {
  std::vector<DriftRecord> drift;
  std::vector<StableStepRecord> largest_stable_h;
};

// Runs this shard's part of the stability study (tasks with index % count ==
// shard index). progress gets a line now and then.
StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress);

}  // namespace rb

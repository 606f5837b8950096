#pragma once
// Where methods fail: long runs whose energy error and rotation defect are
// recorded at log-spaced times (bounded, linear, quadratic growth or blow-up
// can be read off), and for each fixed-step method the largest step below
// which every step of the study stays finite, valid and with a bounded
// energy error and rotation defect. Accuracy is not stability: no error
// against the reference decides it; the whole state must stay bounded, so an
// energy within its bound with R far off SO(3) is not stable.
#include <string>
#include <vector>

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
  double energy_error;     // max |H - H0| over the run / the energy scale; NaN when it failed
  double rotation_defect;  // max ||R^T R - I||_F over the run (the recorded states and the last)
  bool stable;             // ok, energy_error <= energy_fraction and rotation_defect < rotation_defect_bound
};

// The largest h of the ladder h_min, 2 h_min, ... at which the run and every
// run at a smaller h of the ladder were stable.
struct StableStepRecord {
  std::size_t index = 0;
  std::string scene;
  MethodInfo method;
  double h = kNaN;                     // NaN when even h_min was not stable
  double energy_scale = 0.0;           // m g0 r + the starting kinetic energy
  double energy_fraction = 0.0;        // the bound on energy_error
  double rotation_defect_bound = 0.0;  // the bound on rotation_defect
  double rotation_defect = kNaN;       // at h
  bool at_limit = false;               // h is the ladder's top: the method may be stable beyond
  std::vector<StableStepTry> tried;    // by h ascending, up to the first unstable one
};

struct StabilityResults {
  std::vector<DriftRecord> drift;
  std::vector<StableStepRecord> largest_stable_h;
};

// Runs this shard's part of the stability study (tasks with index % count ==
// shard index). progress gets a line now and then.
StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress);

}  // namespace rb

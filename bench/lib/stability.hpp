#pragma once
// Where methods fail: long runs whose energy error and rotation defect are
// recorded at log-spaced times (bounded, linear, quadratic growth or blow-up
// can be read off), and for each fixed-step method on a ladder of steps two
// limits (bench/lib/stability_verdict.hpp, docs/usage.md "Stability"):
// - the blow-up step, the smallest step whose run stops, passes a blow-up
//   bound or grows exponentially by T, read at every horizon T (the same at
//   each where the method has a stability boundary);
// - the drift-limited step h*(T) per horizon, the largest step whose run to
//   T keeps every drift bound (the energy error at the nearest rotation,
//   the rotation defect), each stated with the quantity that crossed.
// Each rung is one run to the last horizon, read at each on its way.
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
  std::vector<double> energy_error_on_group;  // at the nearest rotation (bench/lib/drift.hpp), at each t
  Cost cost;
  double wall_s = 0.0;
};

// One rung: a run at h to the last horizon, in stretches that end at the
// horizons (one step size throughout, each stretch going on from the last
// one's end state), judged at each.
struct StableStepTry {
  double h = kNaN;
  Status status = Status::ok;
  std::string message;     // the run's, where it stopped
  double stop_time = 0.0;  // where the run stopped: the last horizon, a stop, or where the study stopped it
  // the study ended the run at stop_time, before the last horizon: it had
  // blown up, or it had left a drift bound more than blow_up_steps steps
  // before (no later failure counts as a blow-up, and it is out of h*(T)
  // at every longer horizon)
  bool cut_short = false;
  long steps = 0;
  // when each drift quantity first passed its bound (NaN: never, up to stop_time)
  double energy_crossed_at = kNaN, defect_crossed_at = kNaN;
  // when each first passed its blow-up bound (NaN: never)
  double energy_blown_at = kNaN, defect_blown_at = kNaN;
  std::vector<HorizonVerdict> at;  // one per horizon the run was judged at (up to stop_time)
  // the verdict at the last horizon judged: the largest energy errors
  // (flat, which the report calls energy_error, and at the nearest
  // rotation, which the bound reads) and rotation defect, and whether the
  // rung kept every bound and did not blow up there (stable)
  const HorizonVerdict& last() const { return at.back(); }
  bool stable = false;  // within every bound, not blown up, at the last horizon
};

// A rung's standing at horizon T: blown up by T, within every bound to T,
// neither. A rung whose run ended before T keeps its last verdict: blown
// up, or out of its bounds (and not blown up) from there on.
struct RungAt {
  bool blown_up = false;
  bool within = false;
  BlowUp blow_up = BlowUp::none;
  const HorizonVerdict* verdict = nullptr;  // the verdict at T, or the last before it
};
RungAt rung_at(const StableStepTry& rung, std::size_t horizon);

// The blow-up step at one horizon: the smallest rung tried that blew up by T.
struct BlowUpStep {
  double horizon = 0.0;
  double h = kNaN;  // NaN: no rung tried blew up (the ladder's top included)
  BlowUp cause = BlowUp::none;
  Status status = Status::ok;  // the rung's, where it stopped
  // h is the smallest step tried: every rung tried blew up, the true
  // blow-up step may lie below the ladder
  bool smallest_tried = false;
};

// The drift-limited step h*(T): the largest rung that, with every smaller
// rung tried, kept every drift bound and did not blow up to T; with the
// rung above it and what ended it there.
struct DriftLimit {
  double horizon = 0.0;
  double h = kNaN;                  // NaN: not even the smallest rung tried
  bool at_limit = false;            // h is the ladder's top: the method may keep the bounds beyond
  double next_h = kNaN;             // the rung above h (the smallest that failed)
  std::string limited_by;           // at next_h: "energy", "rotation-defect" (the first to cross) or "blow-up"
  BlowUp blow_up = BlowUp::none;    // at next_h, when it blew up
  Status next_status = Status::ok;  // next_h's run's
  double value = kNaN;              // the crossing quantity's largest value to T at next_h
  double bound = kNaN;              // its bound
};

// Both limits of one method on one scene, from the ladder run downward.
struct StableStepRecord {
  std::size_t index = 0;
  std::string scene;
  MethodInfo method;
  std::vector<double> horizons;  // StabilitySpec::horizons
  double energy_scale = 0.0;     // m g0 r + the starting kinetic energy
  StabilityBounds bounds;
  std::vector<BlowUpStep> blow_up;        // one per horizon
  std::vector<DriftLimit> drift_limited;  // one per horizon
  bool blow_up_moves = false;             // the blow-up step differs between horizons
  std::vector<StableStepTry> tried;       // by h ascending
  // the drift-limited step at the last horizon and its accuracy there (the
  // report's h, horizon, energy_error, ...: the records of before)
  double h = kNaN;
  double horizon = 0.0;
  double energy_error = kNaN, energy_error_on_group = kNaN, rotation_defect = kNaN;
  bool at_limit = false;
};

// Fills r's limits (blow_up, drift_limited, blow_up_moves, h, ...) from
// its rungs (tried, ascending h); h_max is the ladder's top.
void read_limits(StableStepRecord& r, double h_max);

struct StabilityResults {
  std::vector<DriftRecord> drift;
  std::vector<StableStepRecord> largest_stable_h;
};

// Runs this shard's part of the stability study (tasks with index % count ==
// shard index). progress gets a line now and then.
StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress);

}  // namespace rb

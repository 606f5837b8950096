#pragma once
// The sweep: every (scene, integrator, h or tolerance) run once for accuracy
// (in parallel over --jobs threads), then timed alone on one thread so that
// timings are not disturbed, in rounds of one repeat of every run. A failing run is a record
// with its status, cost and the time it reached; nothing stops the sweep.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bench/lib/presets.hpp"
#include "bench/lib/reference.hpp"
#include "problems/scene.hpp"

namespace rb {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A scene ready to sweep: the problem, its output grid and its reference.
struct SweepScene {
  Scene scene;
  Problem problem;
  std::string content;  // the scene file's text (cache key)
  std::vector<double> times;
  Reference reference;
};

// Errors at the end of a run against the reference. NaN where not measured
// (the run stopped early) or below the reference's floor (listed by name).
struct RunErrors {
  double contact = kNaN, centre = kNaN, omega = kNaN, rotation = kNaN;
  double floor = 0.0;
  std::vector<std::string> below_floor;
  double scd = kNaN;  // significant correct digits: -log10 of the largest relative error
};

struct RunRecord {
  std::size_t index = 0;  // position in the full (unsharded) sweep
  std::string scene, integrator, family;
  int declared_order = 0, rotation_order = 0;
  bool adaptive = false, needs_jacobian = false;
  double h = kNaN, rtol = kNaN, atol = kNaN;
  Status status = Status::ok;
  std::string message;
  double stop_time = 0.0;
  Cost cost;
  std::vector<double> wall_samples;  // seconds, one per timed repeat
  RunErrors error;
  double energy_drift = kNaN;     // max |H(t) - H(0)| over the outputs
  double rotation_drift = kNaN;   // max ||R^T R - I||_F over the outputs
  FlatState final_state = FlatState::Zero();
  double final_energy = kNaN;
};

// Loads the scenes of a spec (applying its t_end) and their references.
std::vector<SweepScene> prepare_scenes(const SweepSpec& spec);

// One (scene, integrator, h | tol) combination, in sweep order.
struct SweepTask {
  std::size_t index = 0;  // position in the full (unsharded) sweep
  std::size_t scene = 0;
  std::string integrator;
  double h = kNaN;    // fixed-step
  double tol = kNaN;  // adaptive: rtol = atol = tol
};

// The tasks of this shard, in a deterministic order.
std::vector<SweepTask> sweep_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes);

// Runs one task without timing and measures it.
RunRecord run_task(const SweepScene& scene, const SweepTask& task, long max_steps);

// Runs every task (accuracy in parallel, timing serially). progress(done,
// total, phase) is called from the calling thread now and then.
std::vector<RunRecord> run_sweep(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                 const std::function<void(const std::string&)>& progress);

}  // namespace rb

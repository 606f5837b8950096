#pragma once
// The sweep: every (scene, integrator, h or tolerance) run once for accuracy
// (in parallel over --jobs threads), then timed alone on one thread so that
// timings are not disturbed, in rounds of one repeat of every run. A failing run is a record
// with its status, cost and the time it reached; nothing stops the sweep.
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "bench/lib/error_components.hpp"
#include "bench/lib/presets.hpp"
#include "bench/lib/reference.hpp"
#include "bench/lib/reversibility.hpp"
#include "integrators/integrator.hpp"
#include "problems/scene.hpp"

namespace rb {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A scene ready to sweep: the problem, its output grids and its reference.
struct SweepScene {
  Scene scene;
  Problem problem;
  std::string content;              // the scene file's text (cache key)
  std::vector<double> times;        // the error grid: reference, error_max and drift
  std::vector<double> timed_times;  // what the timed call records: t_end, or the --dt-out grid
  Reference reference;
  double omega_scale = 1.0;  // the largest |omega| of the reference (1 where it is at rest)
};

// Errors against the reference: contact, centre, omega and rotation, and
// worst = max(contact / r, centre / r, omega / omega_scale, rotation). NaN
// where not measured (the run stopped early) or below the reference's floor
// (listed by name; worst only when every component is).
struct RunErrors {
  double contact = kNaN, centre = kNaN, omega = kNaN, rotation = kNaN, worst = kNaN;
  // component i of kErrorComponents (bench/lib/error_components.hpp)
  double& component(std::size_t i);
  double component(std::size_t i) const;
  double floor = 0.0;
  std::vector<std::string> below_floor;
  double scd = kNaN;  // significant correct digits: -log10 of the largest relative error
  int points = 0;     // output times measured (1 at t_end)
};

// RunErrors' fields in the order of kErrorComponents.
inline constexpr std::array<double RunErrors::*, kErrorComponentCount> kErrorSlots{
    &RunErrors::contact, &RunErrors::centre, &RunErrors::omega, &RunErrors::rotation};
inline double& RunErrors::component(std::size_t i) { return this->*kErrorSlots.at(i); }
inline double RunErrors::component(std::size_t i) const { return this->*kErrorSlots.at(i); }

// How the largest error over the outputs was obtained: from an untimed run
// that records the error grid, which for fixed-step and dense-output methods
// takes the timed run's steps; same_steps says whether it did.
struct ErrorMaxSource {
  bool same_steps = true;
  long steps = 0;  // accepted steps of the grid run
};

struct RunRecord {
  std::size_t index = 0;  // position in the full (unsharded) sweep
  std::string scene;
  MethodInfo method;       // the integrator's facts
  std::string controller;  // the step-size controller the run used (method.controller unless the sweep chose one)
  double h = kNaN, rtol = kNaN, atol = kNaN;
  Status status = Status::ok;
  std::string message;
  double stop_time = 0.0;
  Cost cost;
  std::size_t timed_outputs = 0;     // output times the timed call records
  std::vector<double> wall_samples;  // seconds, one per timed repeat
  RunErrors error;                   // at t_end, of the run that is timed
  // the largest over the error grid, from a run taking the timed run's
  // steps; where the grid run steps differently (a method that lands on each
  // output), over the timed run's own outputs, and the grid run's in error_grid
  RunErrors error_max;
  ErrorMaxSource error_max_source;
  RunErrors error_grid;
  bool has_error_grid = false;
  double energy_drift = kNaN;    // max |H(t) - H(0)| over the error grid
  double rotation_drift = kNaN;  // max ||R^T R - I||_F over the error grid
  // max |H(polar(R), v, alpha) - H(0)| over the error grid: the energy at the
  // nearest rotation (bench/lib/drift.hpp), what the findings read
  double energy_drift_on_group = kNaN;
  FlatState final_state = FlatState::Zero();
  ReferencePoint final_point{};  // final_state in the error components
  double final_energy = kNaN;
  // a fixed-step run that reached t_end: its reversibility defect, the timed
  // run's end with v -> -v run back over [0, t_end] (docs/model.md, "Time
  // reversal"); none for adaptive and failed runs
  std::optional<ReversibilityDefect> reversibility;
};

// Loads the scenes of a spec (applying its t_end) and, unless told not to,
// their references (without: kind "none", no points); progress, when given,
// gets a line with an estimate before each scene's reference.
std::vector<SweepScene> prepare_scenes(const SweepSpec& spec, bool with_references = true,
                                       const std::function<void(const std::string&)>& progress = {});

// "phase: 3/10 runs, 1.2 s elapsed, about 2.8 s left": progress with an
// estimate from the time per item so far; "phase: 0/10 runs" before the
// first item is done (no time per item yet, so no estimate).
std::string progress_line(const std::string& phase, std::size_t done, std::size_t total, double elapsed_s,
                          const std::string& unit = "runs");

// One (scene, integrator, h | tol) combination, in sweep order.
struct SweepTask {
  std::size_t index = 0;  // position in the full (unsharded) sweep
  std::size_t scene = 0;
  std::string integrator;
  double h = kNaN;                             // fixed-step
  Tolerances tolerances;                       // adaptive: rtol = atol = a tolerance of the spec; none: fixed-step
  const ControllerKind* controller = nullptr;  // RunOptions::controller (nullptr: the method's own)
};

// The step a fixed-step method takes for a ladder value h from 0 to t_end:
// t_end / ceil(t_end / h), h itself where h divides t_end (the order fit and
// the report use it, not the ladder's number).
double step_taken(double h, double t_end);

// The tasks of this shard, in a deterministic order (a fixed-step task's h
// is the step taken).
std::vector<SweepTask> sweep_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes);

// The options of the timed call of a task: the run to t_end recording the
// scene's timed_times (for a fixed-step method, those that are multiples of h).
RunOptions timed_options(const SweepScene& scene, const SweepTask& task, long max_steps);

// How many output times a run with these options records (t_end included).
std::size_t output_count(const Problem& problem, const RunOptions& options);

// Runs one task without timing and measures it: once as it is timed (cost,
// errors at t_end) and, where the timed call does not record the error grid,
// once more recording it (error_max, drift).
RunRecord run_task(const SweepScene& scene, const SweepTask& task, long max_steps);

// The errors at t_end of a run against the scene's reference (record.error,
// its scd): none unless the run reached t_end. rollbench score measures a
// trajectory from another program with it too.
void measure_end(const SweepScene& scene, const RunResult& run, RunRecord& record);

// The largest errors over the error grid (record.error_max) and the drift
// (energy, rotation defect) over the run's outputs, every one of which is a
// time of scene.times; errors only when the run reached t_end.
void measure_grid(const SweepScene& scene, const RunResult& run, RunRecord& record);

// Runs every task (accuracy in parallel, timing serially). progress(done,
// total, phase) is called from the calling thread now and then.
std::vector<RunRecord> run_sweep(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                 const std::function<void(const std::string&)>& progress);

}  // namespace rb

#pragma once
// What the order and tolerance fits read of a run (bench/lib/report.hpp:
// fit_orders, fit_tolerances), typed: made from a sweep's RunRecord, or
// parsed from a report's run entry by merge and score --peers.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/lib/sweep.hpp"

namespace rb {

// What the fits read of a run: a sweep's RunRecord
// (fit_run) or a report's run entry (fit_runs_of, for merge and score
// --peers), so that a merged report's fits equal the unsharded run's. A
// number that is not finite is NaN, as a report's null reads.
struct FitRun {
  std::string scene, integrator;
  bool adaptive = false;
  int declared_order = 0, declared_rotation_order = 0;
  double h = kNaN, rtol = kNaN, stop_time = kNaN;
  long steps = 0;
  RunErrors error;       // at t_end: the components, worst and below_floor
  bool ok = false;       // status ok: the run reached t_end
  ReferencePoint end{};  // the state at stop_time, in the error components (self-convergence compares two)
};

FitRun fit_run(const RunRecord& record);

// The runs of a report's "runs"; throws InputError naming the file and the
// key of an entry that lacks a field the fits read or has one of the wrong
// type.
std::vector<FitRun> fit_runs_of(const nlohmann::json& runs, const std::string& file);

}  // namespace rb

#pragma once
// The JSON report of docs/formats.md ("rollbench.report/2"): provenance, the runs,
// the observed orders, the references and the stability study; and merging
// the reports of shards back into one.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/lib/fit_run.hpp"
#include "bench/lib/group_orders.hpp"
#include "bench/lib/horizon.hpp"
#include "bench/lib/stability.hpp"
#include "bench/lib/sweep.hpp"

namespace rb {

inline constexpr const char* kReportSchema = "rollbench.report/2";

// The report of a sweep. Orders are fitted here, from the fixed-step runs.
nlohmann::json make_report(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                           const std::vector<RunRecord>& runs, const StabilityResults& stability,
                           const HorizonResults& horizon = HorizonResults{});

// A run's "error" or "error_max" object: the components, worst, the floor
// and what lies below it, the points measured, and the reference's kind.
nlohmann::json errors_json(const RunErrors& errors, const std::string& reference_kind);

// A run's entry of "runs" (docs/formats.md, "A run").
nlohmann::json run_json(const RunRecord& record, const std::string& reference_kind);

// Each scene's reference floor (its own error: errors below it are counted
// at the floor, never fitted) and omega_scale (omega's ceiling).
using ReferenceFloors = std::map<std::string, OrderScale>;

// The "orders" entries for the runs of a report: per (scene, integrator) of a
// fixed-step method, the slope of log error on log h per component with its
// 95 % interval, a verdict per component (order_verdict: "as declared",
// "lower", "exact", "inconclusive") and pass: false when a component is
// lower, true when every one is as declared or exact and at least one as
// declared, null otherwise.
nlohmann::json fit_orders(const std::vector<FitRun>& runs, const ReferenceFloors& floors);

// What a report's reference entry gives the order fits: its error,
// omega_scale and, where it has them, its component_errors (NaN otherwise:
// the error stands for each).
OrderScale order_scale_of(const nlohmann::json& reference);

// The "tolerance_fits" entries: per (scene, integrator) of an adaptive
// method, the least-squares line of log10 worst error (at t_end) against
// log10 tolerance over its runs that reached t_end, and step_order: the
// slope of log10 worst error against log10 of the mean step (stop_time /
// steps), the observed order of a method that picks its own steps.
nlohmann::json fit_tolerances(const std::vector<FitRun>& runs);

// The report's "error_components": kErrorComponents with name, label,
// unit and scale.
nlohmann::json error_components_json();

// Joins shard reports: runs, references, stability and horizon records in sweep
// order; the runs parsed into FitRuns, orders and tolerance fits refitted
// as a whole sweep fits them. Throws InputError for reports of another
// schema or of different sweeps, unless every shard 0..n-1 is there once
// (the message names the missing ones), and for a run or reference a fit
// cannot read (naming files[k], "shard report k" where files is short, and
// the key).
nlohmann::json merge_reports(const std::vector<nlohmann::json>& shards, const std::vector<std::string>& files = {});

// Reads a report and checks its schema string; throws InputError naming the
// file.
nlohmann::json read_report(const std::string& path);

// A short text table of a report: per scene and integrator, the observed
// order, the smallest error and its time, and failures.
std::string summary_table(const nlohmann::json& report);

}  // namespace rb

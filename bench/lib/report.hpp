#pragma once
// The report of docs/formats.md ("rollbench.report/2"), typed: provenance,
// the runs, the observed orders, the references and the stability study;
// and merging the reports of shards back into one. Each job in its own file:
// report.cpp (make_report, read_report), report_provenance.cpp (machine,
// build, options, timed_call), run_json.cpp (runs, references and the
// stability study as JSON), report_fits.cpp (orders and tolerance fits),
// report_json.cpp (to_json), report_read.cpp (report_from_json),
// merge_reports.cpp and summary_table.cpp.
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bench/lib/fit_run.hpp"
#include "bench/lib/group_orders.hpp"
#include "bench/lib/horizon.hpp"
#include "bench/lib/order_fit.hpp"
#include "bench/lib/stability.hpp"
#include "bench/lib/sweep.hpp"

namespace rb {

inline constexpr const char* kReportSchema = "rollbench.report/2";

// A run of the report: what the fits, merge and the summary read of it,
// typed, and its entry as written (docs/formats.md, "A run").
struct ReportRun {
  long index = 0;             // its place in the whole sweep: merge sorts by it
  FitRun fit;                 // what the fits read; scene, integrator, status and worst error for the summary
  double wall_median = kNaN;  // wall_s.median: the summary's "its time" (NaN where the entry has none)
  nlohmann::json entry;       // the entry as written: costs, timings, errors, final state (carried through)
};

// A scene's reference entry: its scene, what the order fits take of it, and
// the entry as written (kind, method, cross_check, inertia ...).
struct ReportReference {
  std::string scene;
  OrderScale scale;  // error, omega_scale and component_errors: the fits' floors
  nlohmann::json entry;
};

// An "orders" entry: per (scene, fixed-step integrator), each component's
// fit against the reference, its self-convergence fit and the verdict.
struct ReportOrder {
  std::string scene, integrator;
  int declared = 0, declared_rotation = 0;
  std::array<ComponentOrder, kErrorComponentCount> components;
};

// A "tolerance_fits" entry: per (scene, adaptive integrator), log10 worst
// error on log10 tolerance (line) and on log10 mean step (step_order).
struct ToleranceFit {
  std::string scene, integrator;
  LineFit line, step;
};

// A whole report. Merge, the fits and the summary table read the typed
// members; the sections they only carry through stay JSON, null where a
// report lacks them (then to_json leaves them out).
struct Report {
  nlohmann::json schema = kReportSchema;  // read_report checks it
  // the sweep's options, without "shard": two shards merge only where these
  // are equal, as a whole (any option, the regime grid included)
  nlohmann::json options = nlohmann::json::object();
  std::pair<long, long> shard{0, 1};  // options.shard: [index, count]
  std::vector<ReportReference> references;
  std::vector<ReportRun> runs;
  std::vector<ReportOrder> orders;
  std::vector<ToleranceFit> tolerance_fits;
  // "error_components" is not held: it is written from kErrorComponents.
  nlohmann::json created, git, machine, build;  // provenance (report_provenance.cpp)
  nlohmann::json preset;                        // the preset's name
  nlohmann::json timed_call;                    // what a timed call contains
  nlohmann::json stability;  // {"drift": [...], "largest_stable_h": [...]}: merge sorts them by "index"
  nlohmann::json horizon;    // {"runs": [...]}: merge sorts them by "index"; null in reports older than the study
  nlohmann::json regime;     // the regime grid's scenes and rates (--preset regime only)
  nlohmann::json other = nlohmann::json::object();  // any other top-level key (score --peers' "peers")
};

// The report as written (docs/formats.md).
nlohmann::json to_json(const Report& report);
// For nlohmann: json j = report.
void to_json(nlohmann::json& j, const Report& report);

// A report read back: throws InputError naming file ("the report 'FILE'")
// and the key of what is missing or of the wrong type, options.shard first
// (docs/bad-input.md). Does not check the schema string (read_report does).
Report report_from_json(const nlohmann::json& report, const std::string& file);

// The report of a sweep. Orders are fitted here, from the fixed-step runs.
Report make_report(const SweepSpec& spec, const std::vector<SweepScene>& scenes, const std::vector<RunRecord>& runs,
                   const StabilityResults& stability, const HorizonResults& horizon = HorizonResults{});

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
std::vector<ReportOrder> fit_orders(const std::vector<FitRun>& runs, const ReferenceFloors& floors);
nlohmann::json orders_json(const std::vector<ReportOrder>& orders);

// What a report's reference entry gives the order fits: its error,
// omega_scale and, where it has them, its component_errors (NaN otherwise:
// the error stands for each).
OrderScale order_scale_of(const nlohmann::json& reference);

// The "tolerance_fits" entries: per (scene, integrator) of an adaptive
// method, the least-squares line of log10 worst error (at t_end) against
// log10 tolerance over its runs that reached t_end, and step_order: the
// slope of log10 worst error against log10 of the mean step (stop_time /
// steps), the observed order of a method that picks its own steps.
std::vector<ToleranceFit> fit_tolerances(const std::vector<FitRun>& runs);
nlohmann::json tolerance_fits_json(const std::vector<ToleranceFit>& fits);

// The report's "error_components": kErrorComponents with name, label,
// unit and scale.
nlohmann::json error_components_json();

// Joins shard reports: runs, references, stability and horizon records in sweep
// order; orders and tolerance fits refitted from the runs as a whole sweep
// fits them. Throws InputError for reports of different sweeps, unless
// every shard 0..n-1 is there once (the message names the missing ones)
// and every index of the runs, of the stability and of the horizon records
// is there once (0 .. total - 1 across the shards; one out of range or held
// twice is named with its files: merge_named_reports' files[k] names
// shards[k], "shard report k" where files is short); a scene whose
// references in two shards disagree (t_end, inertia, method) is refused.
// The JSON form reads each shard once (report_from_json, naming files[k],
// "shard report k" where files is short, and the key of what a merge
// cannot read).
Report merge_reports(const std::vector<Report>& shards);
Report merge_named_reports(const std::vector<Report>& shards, const std::vector<std::string>& files);
nlohmann::json merge_reports(const std::vector<nlohmann::json>& shards, const std::vector<std::string>& files = {});

// Reads a report and checks its schema string; throws InputError naming the
// file.
nlohmann::json read_report(const std::string& path);

// A short text table of a report: per scene and integrator, the observed
// order of the headline component, the smallest error and its time, and
// failures.
std::string summary_table(const Report& report);

}  // namespace rb

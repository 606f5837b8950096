// A sweep's report put together from its parts (bench/lib/report.hpp lists
// the files that make each), and a report file read back.
#include "bench/lib/report.hpp"

#include "bench/lib/json_input.hpp"
#include "bench/lib/reference.hpp"
#include "bench/lib/regime_scenes.hpp"
#include "bench/lib/report_parts.hpp"
#include "problems/input_error.hpp"

namespace rb {

using json = nlohmann::json;

Report make_report(const SweepSpec& spec, const std::vector<SweepScene>& scenes, const std::vector<RunRecord>& runs,
                   const StabilityResults& stability, const HorizonResults& horizon) {
  Report report;
  std::map<std::string, std::string> kind;
  ReferenceFloors floors;
  for (const SweepScene& s : scenes) {
    report.references.push_back({s.scene.name, order_scale(s), report_parts::reference_json(s)});
    kind[s.scene.name] = s.reference.kind;
    floors[s.scene.name] = report.references.back().scale;
  }
  std::vector<FitRun> fit_input;
  for (const RunRecord& r : runs) {
    const json entry = run_json(r, kind[r.scene]);
    report.runs.push_back(
        {static_cast<long>(r.index), fit_run(r), report_parts::as_number(entry["wall_s"]["median"]), entry});
    fit_input.push_back(report.runs.back().fit);
  }
  report.options = report_parts::options_json(spec);
  report.shard = {static_cast<long>(spec.shard_index), static_cast<long>(spec.shard_count)};
  report.created = report_parts::utc_now();
  report.git = code_version();
  report.machine = report_parts::machine_json();
  report.build = report_parts::build_json();
  report.preset = spec.preset;
  report.timed_call = report_parts::timed_call_json(spec);
  report.stability = report_parts::stability_json(stability);
  report.horizon = horizon_json(horizon);
  report.orders = fit_orders(fit_input, floors);
  report.tolerance_fits = fit_tolerances(fit_input);
  if (spec.regime) {
    // the grid in the options too, so that shards of two grids refuse to merge
    report.options["regime"] = regime_axes_json(*spec.regime);
    std::vector<Scene> generated;
    for (const SweepScene& s : scenes) generated.push_back(s.scene);
    report.regime = regime_json(*spec.regime, generated);
  }
  return report;
}

json read_report(const std::string& path) {
  const json j = read_json_file(path, kReportInput, "report");
  if (!j.is_object() || !j.contains("schema") || j["schema"] != kReportSchema)
    throw InputError("'" + path + "' is not a " + std::string(kReportSchema) + " report", "schema");
  return j;
}

}  // namespace rb

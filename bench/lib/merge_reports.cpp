// Shard reports joined into the report of the whole sweep, its fits made
// again from all the runs, as the unsharded sweep makes them.
#include <algorithm>

#include "bench/lib/report.hpp"
#include "problems/input_error.hpp"

namespace rb {

using json = nlohmann::json;

namespace {

std::string joined(const std::vector<long>& numbers) {
  std::string text;
  for (const long n : numbers) text += (text.empty() ? "" : ", ") + std::to_string(n);
  return text;
}

// A merge needs every shard of the sweep once: a shard whose job failed is
// named, so that only it has to run again.
void check_every_shard_once(const std::vector<Report>& shards) {
  const long count = shards.front().shard.second;
  std::vector<long> have, missing;
  for (const Report& shard : shards) {
    const auto [index, of] = shard.shard;
    if (of != count)
      throw InputError(
          "the reports come from sweeps cut into " + std::to_string(count) + " and " + std::to_string(of) + " shards",
          "reports");
    if (std::find(have.begin(), have.end(), index) != have.end())
      throw InputError("shard " + std::to_string(index) + " of " + std::to_string(count) + " is given twice",
                       "reports");
    have.push_back(index);
  }
  for (long i = 0; i < count; ++i)
    if (std::find(have.begin(), have.end(), i) == have.end()) missing.push_back(i);
  if (missing.empty()) return;
  std::sort(have.begin(), have.end());
  throw InputError(std::string(missing.size() == 1 ? "shard " : "shards ") + joined(missing) + " of " +
                       std::to_string(count) + (missing.size() == 1 ? " is" : " are") +
                       " missing (given: " + joined(have) + ")",
                   "reports");
}

// The records of a section list of a shard, appended; report_from_json
// checked that each has a number at "index".
void append_records(const json& section, const char* list, json& into) {
  if (section.is_null()) return;  // a horizon section absent from reports older than the study
  for (const json& record : section.at(list)) into.push_back(record);
}

}  // namespace

Report merge_reports(const std::vector<Report>& shards) {
  if (shards.empty()) throw InputError("nothing to merge", "reports");
  check_every_shard_once(shards);
  Report merged = shards.front();
  std::vector<ReportRun> runs;
  std::vector<ReportReference> references;
  json drift = json::array(), stable = json::array(), horizon = json::array();
  for (const Report& s : shards) {
    if (s.options != merged.options)
      throw InputError("the reports come from different sweeps (their options differ)", "reports");
    runs.insert(runs.end(), s.runs.begin(), s.runs.end());
    append_records(s.stability, "drift", drift);
    append_records(s.stability, "largest_stable_h", stable);
    append_records(s.horizon, "runs", horizon);
    for (const ReportReference& r : s.references)
      if (std::none_of(references.begin(), references.end(),
                       [&](const ReportReference& x) { return x.scene == r.scene; }))
        references.push_back(r);
  }
  auto by_index = [](const json& a, const json& b) { return a["index"].get<double>() < b["index"].get<double>(); };
  std::sort(runs.begin(), runs.end(), [](const ReportRun& a, const ReportRun& b) { return a.index < b.index; });
  std::sort(drift.begin(), drift.end(), by_index);
  std::sort(stable.begin(), stable.end(), by_index);
  std::sort(horizon.begin(), horizon.end(), by_index);
  mark_same_series(horizon);  // across the shards: a run's twin may be in another
  // references in the order their scenes first appear in the sweep
  merged.references.clear();
  ReferenceFloors floors;
  std::vector<FitRun> fit_input;
  for (const ReportRun& r : runs) {
    fit_input.push_back(r.fit);
    for (const ReportReference& ref : references)
      if (ref.scene == r.fit.scene && !floors.count(ref.scene)) {
        merged.references.push_back(ref);
        floors[ref.scene] = ref.scale;
      }
  }
  merged.shard = {0, 1};
  merged.runs = runs;
  merged.stability = {{"drift", drift}, {"largest_stable_h", stable}};
  merged.horizon = {{"runs", horizon}};
  merged.orders = fit_orders(fit_input, floors);
  merged.tolerance_fits = fit_tolerances(fit_input);
  return merged;
}

json merge_reports(const std::vector<json>& shards, const std::vector<std::string>& files) {
  if (shards.empty()) throw InputError("nothing to merge", "reports");
  std::vector<Report> parsed;
  for (std::size_t k = 0; k < shards.size(); ++k)
    parsed.push_back(report_from_json(shards[k], k < files.size() ? files[k] : "shard report " + std::to_string(k)));
  return to_json(merge_reports(parsed));
}

}  // namespace rb

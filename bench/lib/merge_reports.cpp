// Shard reports joined into the report of the whole sweep, its fits made
// again from all the runs, as the unsharded sweep makes them.
#include <algorithm>
#include <cstdint>
#include <map>

#include "bench/lib/report.hpp"
#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"

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

// A record of one index space (the runs; the stability study's records; the
// horizon runs) as a shard holds it: its "index" as written, its file and
// its place there.
struct Indexed {
  const json* index;
  const std::string* file;
  std::string where;
};

// Every index of the space is held once across the shards, so the indices
// are 0 .. total - 1 (total: the records the shards hold): one out of range
// (-5, 2^64 - 1) or held twice (two shards of the same runs, however their
// contents compare) is refused, naming the files. Each record had a number
// at "index" (report_from_json).
void check_each_index_once(const char* records, const char* record, const std::vector<Indexed>& space) {
  const std::size_t total = space.size();
  std::vector<const Indexed*> holder(total, nullptr);
  for (const Indexed& r : space) {
    const json& v = *r.index;
    // 2^64 - 1 is an unsigned JSON number, -5 a signed one, 0.5 neither
    const bool whole = v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0);
    const bool in_range = whole && v.get<std::uint64_t>() < total;
    if (!in_range)
      throw InputError("the report '" + *r.file + "': " + r.where + ".index is " + v.dump() +
                           ", not a whole number from 0 to " + std::to_string(total - 1) + " (the shards hold " +
                           std::to_string(total) + " " + records + ", each index once)",
                       "reports");
    const Indexed*& first = holder[v.get<std::size_t>()];
    if (first != nullptr)
      throw InputError(std::string(record) + " index " + v.dump() + " is in both '" + *first->file + "' (" +
                           first->where + ") and '" + *r.file + "' (" + r.where + "): each is in one shard only",
                       "reports");
    first = &r;
  }
}

// The records of section.list of each shard that has the section (a
// horizon section is absent from reports older than the study).
void add_records(std::vector<Indexed>& space, const json& section, const char* name, const char* list,
                 const std::string& file) {
  if (!section.is_object() || !section.contains(list)) return;
  const json& items = section[list];
  for (std::size_t i = 0; i < items.size(); ++i)
    space.push_back({&items[i].at("index"), &file, std::string(name) + "." + list + "[" + std::to_string(i) + "]"});
}

void check_indices(const std::vector<Report>& shards, const std::vector<std::string>& files) {
  std::vector<Indexed> runs, stability, horizon;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const Report& s = shards[k];
    for (std::size_t i = 0; i < s.runs.size(); ++i)
      runs.push_back({&s.runs[i].entry.at("index"), &files[k], "runs[" + std::to_string(i) + "]"});
    // the drift runs and the largest-stable-h searches count on from one index
    add_records(stability, s.stability, "stability", "drift", files[k]);
    add_records(stability, s.stability, "stability", "largest_stable_h", files[k]);
    add_records(horizon, s.horizon, "horizon", "runs", files[k]);
  }
  check_each_index_once("runs", "run", runs);
  check_each_index_once("stability records", "stability record", stability);
  check_each_index_once("horizon runs", "horizon run", horizon);
}

// One name, one scene: each shard's reference of a scene must give the
// facts of the same scene (its t_end, ball and reference method), or two
// scenes of one name went into the shards.
void check_one_scene_per_name(const std::vector<Report>& shards, const std::vector<std::string>& files) {
  std::map<std::string, std::pair<const ReportReference*, const std::string*>> first;
  for (std::size_t k = 0; k < shards.size(); ++k)
    for (const ReportReference& r : shards[k].references) {
      const auto [at, inserted] = first.try_emplace(r.scene, &r, &files[k]);
      if (inserted) continue;
      for (const char* key : {"t_end", "inertia", "r_feeds_back", "kind", "method"}) {
        const json none;
        const json& a = at->second.first->entry.contains(key) ? at->second.first->entry[key] : none;
        const json& b = r.entry.contains(key) ? r.entry[key] : none;
        if (a != b)
          throw InputError("scene '" + escaped_excerpt(r.scene) + "' differs between '" + *at->second.second +
                               "' and '" + files[k] + "' (its reference's " + key + ": " + a.dump() + " and " +
                               b.dump() + "): two scenes with one name",
                           "reports");
      }
    }
}

// The records of a section list of a shard, appended; report_from_json
// checked that each has a number at "index".
void append_records(const json& section, const char* list, json& into) {
  if (section.is_null()) return;  // a horizon section absent from reports older than the study
  for (const json& record : section.at(list)) into.push_back(record);
}

}  // namespace

Report merge_reports(const std::vector<Report>& shards) { return merge_named_reports(shards, {}); }

Report merge_named_reports(const std::vector<Report>& shards, const std::vector<std::string>& files) {
  if (shards.empty()) throw InputError("nothing to merge", "reports");
  check_every_shard_once(shards);
  for (const Report& s : shards)
    if (s.options != shards.front().options)
      throw InputError("the reports come from different sweeps (their options differ)", "reports");
  std::vector<std::string> names = files;  // "shard report k" where files is short
  for (std::size_t k = names.size(); k < shards.size(); ++k) names.push_back("shard report " + std::to_string(k));
  check_indices(shards, names);
  check_one_scene_per_name(shards, names);
  Report merged = shards.front();
  std::vector<ReportRun> runs;
  std::vector<ReportReference> references;
  json drift = json::array(), stable = json::array(), horizon = json::array();
  for (const Report& s : shards) {
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
  std::vector<std::string> names;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    names.push_back(k < files.size() ? files[k] : "shard report " + std::to_string(k));
    parsed.push_back(report_from_json(shards[k], names.back()));
  }
  return to_json(merge_named_reports(parsed, names));
}

}  // namespace rb

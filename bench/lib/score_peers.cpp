#include "bench/lib/score_peers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "bench/lib/json_input.hpp"
#include "bench/lib/report.hpp"
#include "bench/lib/score.hpp"
#include "bench/lib/sweep.hpp"
#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"

namespace rb {

namespace {

using json = nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string short_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// Reads the fields of the peer file, refusing what is missing or of the
// wrong type with the key ("runs[3].rtol") and the file.
class PeerFields {
 public:
  explicit PeerFields(std::string file) : file_(std::move(file)) {}

  const json& at(const json& j, const std::string& key, const std::string& where) const {
    if (!j.is_object() || !j.contains(key)) refuse(where + key, "is missing");
    return j.at(key);
  }
  std::string text(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_string()) refuse(where + key, "must be a string");
    return v.get<std::string>();
  }
  double number(const json& j, const std::string& key, const std::string& where, bool null_ok = false) const {
    const json& v = at(j, key, where);
    if (null_ok && v.is_null()) return kNaN;
    if (!v.is_number()) refuse(where + key, null_ok ? "must be a number or null" : "must be a number");
    return v.get<double>();
  }
  long count(const json& j, const std::string& key, const std::string& where) const {
    const double v = number(j, key, where);
    if (!(v >= 0.0 && v == std::floor(v) && v < 1e18)) refuse(where + key, "must be a whole number >= 0");
    return static_cast<long>(v);
  }
  [[noreturn]] void refuse(const std::string& key, const std::string& what) const {
    throw InputError("'" + file_ + "': " + what, key);
  }

 private:
  std::string file_;
};

json read_json(const std::string& path) { return read_json_file(path, kPeerFileInput, "peers"); }

// A trajectory a peer file names: a relative path inside the peer file's own
// folder (no absolute path, no "..", no symlink out of it), a regular file
// of at most kTrajectoryInput's limit. Its text, or an InputError.
std::string read_peer_trajectory(const std::filesystem::path& folder, const std::string& name, const std::string& key,
                                 const PeerFields& f) {
  namespace fs = std::filesystem;
  const fs::path relative(name);
  bool climbs = relative.is_absolute() || name.empty() || name.find('\0') != std::string::npos;
  for (const fs::path& part : relative) climbs = climbs || part == "..";
  if (climbs) f.refuse(key, "'" + escaped_excerpt(name) + "' is not a path inside the peer file's folder");
  std::error_code ec;
  const fs::path base = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
  const fs::path resolved = fs::weakly_canonical(base / relative, ec);
  const auto [end, ignored] = std::mismatch(base.begin(), base.end(), resolved.begin(), resolved.end());
  if (ec || end != base.end()) f.refuse(key, "'" + escaped_excerpt(name) + "' leads out of the peer file's folder");
  return read_input_file(resolved.string(), kTrajectoryInput, key);
}

Status status_named(const std::string& name, const PeerFields& f, const std::string& key) {
  for (Status s : {Status::ok, Status::diverged, Status::lift_off, Status::curvature, Status::domain,
                   Status::step_underflow, Status::max_steps, Status::error})
    if (status_name(s) == name) return s;
  f.refuse(key, "'" + escaped_excerpt(name) +
                    "' is not a report status (ok, diverged, lift-off, curvature, domain, step-underflow, "
                    "max-steps, error)");
}

// The peer's facts about one solve, and its trajectory scored.
RunRecord peer_run(const json& p, const std::string& where, const SweepScene& s, double spacing,
                   const std::filesystem::path& folder, const PeerFields& f) {
  RunRecord r;
  r.scene = s.scene.name;
  r.method.name = f.text(p, "integrator", where);
  r.method.family = f.text(p, "family", where);
  r.method.declared_order = static_cast<int>(f.count(p, "declared_order", where));
  r.method.rotation_order = r.method.declared_order;
  r.method.adaptive = true;
  const json& jac = f.at(p, "needs_jacobian", where);
  if (!jac.is_boolean()) f.refuse(where + "needs_jacobian", "must be true or false");
  r.method.needs_jacobian = jac.get<bool>();
  r.controller = "library";
  r.rtol = f.number(p, "rtol", where);
  r.atol = f.number(p, "atol", where);
  r.cost.steps = f.count(p, "steps", where);
  r.cost.rhs_evals = f.count(p, "rhs_evals", where);
  r.cost.jacobian_evals = f.count(p, "jacobian_evals", where);
  r.cost.validity_checks = f.count(p, "validity_checks", where);
  const json& wall = f.at(p, "wall_s", where);
  if (!wall.is_array() || wall.empty()) f.refuse(where + "wall_s", "must be a list of the timed solves' seconds");
  for (const json& w : wall) {
    if (!w.is_number() || !(w.get<double>() >= 0.0)) f.refuse(where + "wall_s", "must hold numbers >= 0");
    r.wall_samples.push_back(w.get<double>());
  }
  const std::string peer_status = f.text(p, "status", where);
  r.status = status_named(peer_status, f, where + "status");
  r.message = f.text(p, "message", where);

  const std::filesystem::path csv_path = folder / f.text(p, "trajectory", where);
  std::istringstream csv(read_peer_trajectory(folder, f.text(p, "trajectory", where), where + "trajectory", f));
  ScoredTrajectory scored = score_rows(s, spacing, csv, csv_path.string());
  RunErrors error_max = scored.record.error_max;
  r.error = scored.record.error;
  r.error_max = error_max;
  r.energy_drift = scored.record.energy_drift;
  r.rotation_drift = scored.record.rotation_drift;
  r.energy_drift_on_group = scored.record.energy_drift_on_group;
  if (r.status == Status::ok && scored.status != "ok") {
    // the solve said it got there, the file says otherwise
    r.status = scored.status == "diverged" ? Status::diverged : Status::error;
    r.message = scored.message;
  }
  if (r.status != Status::ok) r.error = r.error_max = RunErrors{};  // a failed run has no errors, as in the report
  r.stop_time = scored.run.output.t.empty() ? 0.0 : scored.run.output.t.back();
  if (p.contains("stop_time") && p["stop_time"].is_number()) r.stop_time = p["stop_time"].get<double>();
  r.final_state = scored.run.output.y.empty() ? s.problem.y0() : scored.run.output.y.back();
  r.timed_outputs = s.times.size();  // the timed solve records the whole grid
  r.error_max_source = {true, r.cost.steps};
  return r;
}

// The peer's own facts a report run does not have, under "peer".
json peer_facts(const json& p, const std::string& peer, const json& rhs_cost, const RunRecord& r) {
  json facts = {{"name", peer}};
  for (const char* key : {"method", "declared_order_text", "lu_decompositions", "options"})
    if (p.contains(key)) facts[key] = p[key];
  // what the bare evaluations through the peer's binding cost, for readers to subtract
  // per call through the peer's interpreter (Python's ctypes wrapper, Octave's oct-file)
  const double rhs_s = rhs_cost.value("interpreter_s_per_call", rhs_cost.value("python_s_per_call", kNaN));
  const double jac_s = rhs_cost.value("jacobian_s_per_call", kNaN);
  facts["rhs_cost_s"] = number_or_null(rhs_s * static_cast<double>(r.cost.rhs_evals));
  facts["jacobian_cost_s"] = number_or_null(jac_s * static_cast<double>(r.cost.jacobian_evals));
  return facts;
}

// The effective t_end and grid spacing of a scene in a report.
void check_same_grid(const json& report, const std::string& into, const SweepScene& s, double spacing) {
  const json* reference = nullptr;
  for (const json& ref : report.at("references"))
    if (ref.value("scene", "") == s.scene.name) reference = &ref;
  if (!reference)
    throw InputError("the report '" + into + "' has no runs on scene '" + s.scene.name + "' the peer solved", "into");
  const double t_end = reference->value("t_end", kNaN);
  if (t_end != s.scene.t_end)
    throw InputError("the peer solved scene '" + s.scene.name + "' to t_end = " + short_number(s.scene.t_end) +
                         ", the report '" + into + "' to " + short_number(t_end) + " (give the peer the run's t_end)",
                     "into");
  const json& o = report.at("options");
  const double report_spacing =
      o.value("dt_out", json()).is_number() ? o["dt_out"].get<double>() : o.value("error_dt", 0.25);
  if (std::abs(report_spacing - spacing) > 1e-12 * spacing)
    throw InputError("the peer's output grid is every " + short_number(spacing) + ", the report '" + into +
                         "' has every " + short_number(report_spacing),
                     "into");
}

}  // namespace

json score_peers(const std::string& peers_path, const std::string& into, const std::string& cache_dir) {
  const json peers = read_json(peers_path);
  const PeerFields f(peers_path);
  if (f.text(peers, "schema", "") != kPeersSchema) f.refuse("schema", "is not \"" + std::string(kPeersSchema) + "\"");
  const std::string peer = f.text(peers, "peer", "");
  const json& runs = f.at(peers, "runs", "");
  if (!runs.is_array() || runs.empty()) f.refuse("runs", "must be a list of one or more solves");

  SweepSpec spec;
  spec.preset = "peers";
  spec.cache_dir = cache_dir;
  const double t_end = f.number(peers, "t_end", "", true), dt_out = f.number(peers, "dt_out", "", true);
  spec.t_end = std::isfinite(t_end) ? t_end : 0.0;
  spec.dt_out = std::isfinite(dt_out) ? dt_out : 0.0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string scene = f.text(runs[i], "scene", "runs[" + std::to_string(i) + "].");
    if (std::find(spec.scenes.begin(), spec.scenes.end(), scene) == spec.scenes.end()) spec.scenes.push_back(scene);
  }
  const double spacing = spec.dt_out > 0.0 ? spec.dt_out : spec.error_dt;
  json report;
  if (!into.empty()) report = read_report(into);  // before the references: a wrong report fails fast
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  std::map<std::string, const SweepScene*> by_name;
  for (std::size_t i = 0; i < scenes.size(); ++i) by_name[spec.scenes[i]] = &scenes[i];
  if (into.empty()) {
    report = make_report(spec, scenes, {}, {});
  } else {
    for (const SweepScene& s : scenes) check_same_grid(report, into, s, spacing);
  }

  std::map<std::string, json> rhs_costs;  // per scene as the peer named it
  if (peers.contains("rhs_cost") && peers["rhs_cost"].is_array())
    for (const json& c : peers["rhs_cost"])
      if (c.contains("scene") && c["scene"].is_string()) rhs_costs[c["scene"].get<std::string>()] = c;
  const std::filesystem::path folder = std::filesystem::path(peers_path).parent_path();
  json& report_runs = report["runs"];
  // the fits read the report's runs as a merge does, and the peer's as a sweep does
  std::vector<FitRun> fit_input = into.empty() ? std::vector<FitRun>{} : fit_runs_of(report_runs, into);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string where = "runs[" + std::to_string(i) + "].";
    const std::string scene = runs[i]["scene"].get<std::string>();
    const SweepScene& s = *by_name.at(scene);
    RunRecord r = peer_run(runs[i], where, s, spacing, folder, f);
    r.index = report_runs.size();
    json j = run_json(r, s.reference.kind);
    j["rejected"] = nullptr;  // a library that does not say
    j["peer"] = peer_facts(runs[i], peer, rhs_costs.count(scene) ? rhs_costs[scene] : json::object(), r);
    report_runs.push_back(j);
    fit_input.push_back(fit_run(r));
  }
  report["tolerance_fits"] = tolerance_fits_json(fit_tolerances(fit_input));
  report["error_components"] = error_components_json();  // what the peer's runs were measured in
  json entry = {{"peer", peer}, {"file", peers_path}};
  for (const char* key : {"versions", "library", "abi_version", "timing", "rhs_cost"})
    if (peers.contains(key)) entry[key] = peers[key];
  report["peers"].push_back(entry);
  return report;
}

}  // namespace rb

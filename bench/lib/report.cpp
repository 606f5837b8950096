#include "bench/lib/report.hpp"

#include <gsl/gsl_version.h>
#include <sys/utsname.h>

#include <Eigen/Core>
#include <algorithm>
#include <boost/version.hpp>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "bench/lib/group_orders.hpp"
#include "bench/lib/json_input.hpp"
#include "bench/lib/order_fit.hpp"
#include "bench/lib/regime_scenes.hpp"
#include "problems/input_error.hpp"
#include "problems/utf8.hpp"

namespace rb {

using json = nlohmann::json;

namespace {

// NaN is "not measured": null in JSON.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string first_line_of(const std::string& path, const std::string& prefix) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  return "unknown";
}

json machine() {
  utsname u{};
  uname(&u);
  std::ifstream loadavg("/proc/loadavg");
  double l1 = kNaN, l5 = kNaN, l15 = kNaN;
  loadavg >> l1 >> l5 >> l15;
  return {{"cpu", first_line_of("/proc/cpuinfo", "model name")},
          {"cores", std::thread::hardware_concurrency()},
          {"os", std::string(u.sysname) + " " + u.release + " " + u.machine},
          {"load", {number(l1), number(l5), number(l15)}}};
}

json build() {
  return {{"compiler", std::string("g++ ") + __VERSION__},
          {"flags", RB_BUILD_FLAGS},
          {"type", RB_BUILD_TYPE},
          {"preset", RB_BUILD_PRESET},
          {"libraries",
           {{"boost", BOOST_LIB_VERSION},
            {"gsl", GSL_VERSION},
            {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                          std::to_string(EIGEN_MINOR_VERSION)},
            {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                                  std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                                  std::to_string(NLOHMANN_JSON_VERSION_PATCH)}}}};
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

// What fails a stability rung, as the report states it.
json bounds_json(const StabilityBounds& b) {
  return {{"energy", b.energy_fraction},
          {"rotation_defect", b.rotation_defect},
          {"growth_exponent", b.growth_exponent},
          {"growth_floor", b.growth_floor}};
}

json options_of(const SweepSpec& s) {
  const StabilitySpec& st = s.stability;
  // scene paths as the user typed them: any bytes, text here
  std::vector<std::string> scenes;
  for (const std::string& scene : s.scenes) scenes.push_back(valid_utf8(scene));
  return {{"preset", s.preset},
          {"scenes", scenes},
          {"integrators", s.integrators},
          {"h", s.hs},
          {"tol", s.tols},
          {"t_end", number(s.t_end > 0 ? s.t_end : kNaN)},
          {"dt_out", number(s.dt_out > 0 ? s.dt_out : kNaN)},
          {"error_dt", s.error_dt},
          {"repeats", s.repeats},
          {"repeat_budget_s", s.repeat_budget_s},
          {"jobs", s.jobs},
          {"max_steps", s.max_steps},
          {"controller", s.controller ? json(s.controller->name) : json(nullptr)},
          {"stability",
           {{"enabled", st.enabled},
            {"scenes", st.scenes},
            {"integrators", st.integrators},
            {"drift_h", st.drift_h},
            {"drift_t_end", st.drift_t_end},
            {"search_h_max", st.search_h_max},
            {"search_h_min", st.search_h_min},
            {"search_t_end", st.search_t_end},
            {"search_outputs", st.search_outputs},
            {"bounds", bounds_json(st.bounds)}}},
          {"horizon", horizon_options_json(s.horizon)}};
}

}  // namespace

json errors_json(const RunErrors& e, const std::string& reference_kind) {
  json j = {{"reference", reference_kind},
            {"worst", number(e.worst)},
            {"floor", e.floor},
            {"below_floor", e.below_floor},
            {"points", e.points}};
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) j[kErrorComponents[i].name] = number(e.component(i));
  return j;
}

json error_components_json() {
  json list = json::array();
  for (const ErrorComponent& c : kErrorComponents)
    list.push_back({{"name", c.name}, {"label", c.label}, {"unit", c.unit}, {"scale", scale_name(c.scale)}});
  return list;
}

namespace {

// A fixed-step run's reversibility defect: its distances back at the start,
// or the status and message of a leg back that failed.
json reversibility_json(const ReversibilityDefect& d) {
  if (d.status != Status::ok)
    return {{"status", std::string(status_name(d.status))}, {"message", valid_utf8(d.message)}};
  return {{"status", "ok"},
          {"contact", number(d.contact)},
          {"rotation", number(d.rotation)},
          {"momentum", number(d.momentum)},
          {"worst", number(d.worst())}};
}

}  // namespace

json run_json(const RunRecord& r, const std::string& reference_kind) {
  std::vector<double> samples = r.wall_samples;
  const Mat3 R = rotation_of(r.final_state);
  const MethodInfo& m = r.method;
  return {
      {"index", r.index},
      {"scene", r.scene},
      {"integrator", m.name},
      {"family", m.family},
      {"declared_order", m.declared_order},
      {"declared_rotation_order", m.rotation_order},
      {"adaptive", m.adaptive},
      {"needs_jacobian", m.needs_jacobian},
      {"controller", r.controller},
      {"tableau", m.tableau.empty() ? json(nullptr) : json(m.tableau)},
      {"on_group", m.on_group},
      {"h", number(r.h)},
      {"rtol", number(r.rtol)},
      {"atol", number(r.atol)},
      {"status", std::string(status_name(r.status))},
      {"message", r.message},
      {"stop_time", r.stop_time},
      {"steps", r.cost.steps},
      {"rejected", r.cost.rejected},
      {"rhs_evals", r.cost.rhs_evals},
      {"jacobian_evals", r.cost.jacobian_evals},
      {"exp_evals", r.cost.exp_evals},
      {"dexpinv_evals", r.cost.dexpinv_evals},
      {"validity_checks", r.cost.validity_checks},
      {"newton",
       m.newton_tol > 0.0
           ? json{{"tol", m.newton_tol}, {"iterations", r.cost.newton_iterations}, {"failures", r.cost.newton_failures}}
           : json(nullptr)},
      {"wall_s",
       {{"median", number(median(samples))},
        {"min", number(samples.empty() ? kNaN : *std::min_element(samples.begin(), samples.end()))},
        {"max", number(samples.empty() ? kNaN : *std::max_element(samples.begin(), samples.end()))},
        {"repeats", samples.size()},
        {"samples", samples}}},
      {"timed_outputs", r.timed_outputs},
      {"error", errors_json(r.error, reference_kind)},
      {"error_max", errors_json(r.error_max, reference_kind)},
      {"error_max_run", {{"same_steps", r.error_max_source.same_steps}, {"steps", r.error_max_source.steps}}},
      {"error_grid", r.has_error_grid ? errors_json(r.error_grid, reference_kind) : json(nullptr)},
      {"scd", number(r.error.scd)},
      {"reversibility", r.reversibility ? reversibility_json(*r.reversibility) : json(nullptr)},
      {"drift", {{"energy", number(r.energy_drift)}, {"rotation_defect", number(r.rotation_drift)}}},
      {"final",
       {{"t", r.stop_time},
        {"contact", {r.final_state[kOffsetAlpha], r.final_state[kOffsetAlpha + 1]}},
        {"centre",
         {number(r.final_point.centre.x()), number(r.final_point.centre.y()), number(r.final_point.centre.z())}},
        {"omega", {number(r.final_point.omega.x()), number(r.final_point.omega.y()), number(r.final_point.omega.z())}},
        {"R", {{R(0, 0), R(0, 1), R(0, 2)}, {R(1, 0), R(1, 1), R(1, 2)}, {R(2, 0), R(2, 1), R(2, 2)}}}}}};
}

namespace {

// What each timed call contains, the same for every method.
json timed_call(const SweepSpec& spec) {
  const std::string outputs = spec.dt_out > 0.0
                                  ? "every multiple of dt_out up to t_end (for a fixed-step method, those "
                                    "that are multiples of h)"
                                  : "t_end only";
  return {
      {"outputs", outputs},
      {"contains",
       "one integrate() call from t = 0 to t_end recording the outputs above: every step with its rhs "
       "evaluations, the model's validity check of the start and of each accepted state (validity_checks), "
       "the finiteness and domain check of each recorded output, and copying the recorded states; not the untimed "
       "warm-up call before it, not the error measurement; "
       "for a --stepper plug-in run in its own process, the time the child measured around the integration after an "
       "untimed warm-up run in it (not the fork, the pipe or the warm-up)"},
      {"error_max",
       "the largest error over the timed run's steps: from an untimed run recording every multiple "
       "of error_dt (dt_out when given) up to t_end where that run takes the timed run's steps "
       "(fixed-step and dense-output methods), else over the timed run's own outputs; then "
       "error_max_run.same_steps is false and error_grid holds the grid run's errors"}};
}

json growth_json(const GrowthShape& g) {
  return {{"p_early", number(g.p_early)}, {"p_late", number(g.p_late)}, {"exponential", g.exponential}};
}

json stability_json(const StabilityResults& s) {
  json drift = json::array(), stable = json::array();
  for (const DriftRecord& d : s.drift)
    drift.push_back({{"index", d.index},
                     {"scene", d.scene},
                     {"integrator", d.method.name},
                     {"family", d.method.family},
                     {"h", d.h},
                     {"status", std::string(status_name(d.status))},
                     {"message", d.message},
                     {"stop_time", d.stop_time},
                     {"t", d.t},
                     {"energy_error", d.energy_error},
                     {"rotation_defect", d.rotation_defect},
                     {"steps", d.cost.steps},
                     {"rhs_evals", d.cost.rhs_evals},
                     {"wall_s", d.wall_s}});
  for (const StableStepRecord& r : s.largest_stable_h) {
    json tried = json::array();
    for (const StableStepTry& t : r.tried)
      tried.push_back(
          {{"h", t.h},
           {"status", std::string(status_name(t.status))},
           {"message", t.message},
           {"stop_time", t.stop_time},
           {"energy_error", number(t.energy_error)},
           {"rotation_defect", number(t.rotation_defect)},
           {"growth",
            {{"energy_error", growth_json(t.energy_growth)}, {"rotation_defect", growth_json(t.defect_growth)}}},
           {"failure", t.stable ? json(nullptr) : json(failure_name(t.failure))},
           {"stable", t.stable}});
    stable.push_back({{"index", r.index},
                      {"scene", r.scene},
                      {"integrator", r.method.name},
                      {"family", r.method.family},
                      {"h", number(r.h)},
                      {"horizon", r.horizon},
                      {"at_limit", r.at_limit},
                      {"energy_error", number(r.energy_error)},
                      {"rotation_defect", number(r.rotation_defect)},
                      {"energy_scale", r.energy_scale},
                      {"thresholds", bounds_json(r.bounds)},
                      {"tried", tried}});
  }
  return {{"drift", drift}, {"largest_stable_h", stable}};
}

double as_number(const json& j) { return j.is_number() ? j.get<double>() : kNaN; }

// A reference's own error per component, by component name.
json component_errors_json(const Reference& reference) {
  json out = json::object();
  for (std::size_t i = 0; i < kErrorComponentCount; ++i)
    out[kErrorComponents[i].name] = number(reference.component_error[i]);
  return out;
}

// The ball's principal moments as the scene gives them; null for the
// homogeneous ball (I = 2/5 m r^2 about every axis), where R does not enter
// the dynamics.
json inertia_json(const SweepScene& s) {
  if (!s.scene.ball.inertia) return nullptr;
  const Vec3& I = *s.scene.ball.inertia;
  return {I.x(), I.y(), I.z()};
}

using RunKey = std::pair<std::string, std::string>;  // (scene, integrator)

// The runs of fixed-step (adaptive = false) or adaptive methods per (scene,
// integrator), keys in order of first appearance.
struct RunGroups {
  std::vector<RunKey> keys;
  std::map<RunKey, std::vector<const FitRun*>> members;
};

RunGroups group_runs(const std::vector<FitRun>& runs, bool adaptive) {
  RunGroups g;
  for (const FitRun& r : runs) {
    if (r.adaptive != adaptive) continue;
    const RunKey key{r.scene, r.integrator};
    if (!g.members.count(key)) g.keys.push_back(key);
    g.members[key].push_back(&r);
  }
  return g;
}

}  // namespace

json fit_tolerances(const std::vector<FitRun>& runs) {
  const RunGroups groups = group_runs(runs, true);
  json fits = json::array();
  for (const RunKey& key : groups.keys) {
    std::vector<double> log_tol, log_error;
    for (const FitRun* r : groups.members.at(key)) {
      const double tol = r->rtol, e = r->error.worst;
      if (tol > 0.0 && e > 0.0) log_tol.push_back(std::log10(tol)), log_error.push_back(std::log10(e));
    }
    const LineFit line = fit_line(log_tol, log_error);
    // the observed order of a method whose step it picks itself: the slope
    // of log error against log mean step, t_end / steps, over the same runs
    std::vector<double> log_step, log_step_error;
    for (const FitRun* r : groups.members.at(key)) {
      const double e = r->error.worst, steps = static_cast<double>(r->steps);
      const double t = r->stop_time;
      if (e > 0.0 && steps > 0.0 && t > 0.0)
        log_step.push_back(std::log10(t / steps)), log_step_error.push_back(std::log10(e));
    }
    const LineFit step = fit_line(log_step, log_step_error);
    fits.push_back({{"scene", key.first},
                    {"integrator", key.second},
                    {"slope", number(line.slope)},
                    {"intercept", number(line.intercept)},
                    {"residual", number(line.residual)},
                    {"ci95", number(line.slope_ci95)},
                    {"points", line.points},
                    {"step_order",
                     {{"slope", number(step.slope)},
                      {"ci95", number(step.slope_ci95)},
                      {"residual", number(step.residual)},
                      {"points", step.points}}}});
  }
  return fits;
}

namespace {

// A fit as a report holds it: the slope with its 95 % interval and window,
// the halving and rung slopes, whether the halvings agree (asymptotic), null where no
// slope was fitted.
json order_fit_json(const OrderFit& fit) {
  json j = {{"points", std::max(0, fit.points)},    {"at_plateau", fit.at_floor},
            {"halving_slopes", fit.halving_slopes}, {"rung_slopes", fit.rung_slopes},
            {"asymptotic", fit.asymptotic},         {"all_at_plateau", fit.all_at_plateau}};
  if (!std::isfinite(fit.slope)) {
    j["slope"] = nullptr;
    j["ci95"] = nullptr;
    return j;
  }
  j["slope"] = fit.slope;
  j["ci95"] = number(fit.slope_ci95);
  j["h_min"] = fit.h_min;
  j["h_max"] = fit.h_max;
  j["r2"] = fit.r2;
  j["residual"] = fit.residual;
  return j;
}

}  // namespace

OrderScale order_scale_of(const json& reference) {
  const auto field = [&](const char* key) { return reference.contains(key) ? reference[key] : json(); };
  OrderScale scale{as_number(field("error")), as_number(field("omega_scale"))};
  if (!field("component_errors").is_object()) return scale;
  const json& each = reference["component_errors"];
  for (std::size_t i = 0; i < kErrorComponentCount; ++i)
    if (each.contains(kErrorComponents[i].name)) scale.component_floor[i] = as_number(each[kErrorComponents[i].name]);
  return scale;
}

json fit_orders(const std::vector<FitRun>& runs, const ReferenceFloors& floors) {
  const RunGroups groups = group_runs(runs, false);
  json orders = json::array();
  for (const RunKey& key : groups.keys) {
    const std::vector<const FitRun*>& group = groups.members.at(key);
    const FitRun& first = *group.front();
    const auto found = floors.find(key.first);
    const auto components = group_orders(group, found != floors.end() ? found->second : OrderScale{});
    json observed, ci95, fits, self, verdicts, reasons;
    // pass: every component as declared or exact, at least one as declared
    bool lower = false, all_as_declared = true, any_as_declared = false;
    for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
      const std::string c = kErrorComponents[i].name;
      const ComponentOrder& o = components[i];
      verdicts[c] = o.judgement.verdict;
      reasons[c] = o.judgement.reason.empty() ? json(nullptr) : json(o.judgement.reason);
      lower = lower || o.judgement.verdict == "lower";
      all_as_declared = all_as_declared && (o.judgement.verdict == "as declared" || o.judgement.verdict == "exact");
      any_as_declared = any_as_declared || o.judgement.verdict == "as declared";
      observed[c] = std::isfinite(o.reference.slope) ? json(o.reference.slope) : json(nullptr);
      ci95[c] = std::isfinite(o.reference.slope) ? number(o.reference.slope_ci95) : json(nullptr);
      fits[c] = order_fit_json(o.reference);
      self[c] = order_fit_json(o.self);
    }
    orders.push_back({{"scene", key.first},
                      {"integrator", key.second},
                      {"declared", first.declared_order},
                      {"declared_rotation", first.declared_rotation_order},
                      {"observed", observed},
                      {"ci95", ci95},
                      {"fit", fits["contact"]},
                      {"fits", fits},
                      {"self_convergence", self},
                      {"plateau",
                       {{"floor_multiple", kFloorMultiple},
                        {"rounding_multiple", kRoundingMultiple},
                        {"rounding_per_step", kRoundingPerStep}}},
                      {"verdict", verdicts},
                      {"inconclusive_reason", reasons},
                      {"pass", lower                                ? json(false)
                               : all_as_declared && any_as_declared ? json(true)
                                                                    : json(nullptr)}});
  }
  return orders;
}

namespace {

// What a report derives from its runs, written alike by a sweep and by a
// merge of its shards: the component list, the orders and the tolerance fits.
void put_fits(json& report, const std::vector<FitRun>& runs, const ReferenceFloors& floors) {
  report["error_components"] = error_components_json();
  report["orders"] = fit_orders(runs, floors);
  report["tolerance_fits"] = fit_tolerances(runs);
}

}  // namespace

json make_report(const SweepSpec& spec, const std::vector<SweepScene>& scenes, const std::vector<RunRecord>& runs,
                 const StabilityResults& stability, const HorizonResults& horizon) {
  json references = json::array();
  for (const SweepScene& s : scenes)
    references.push_back({{"scene", s.scene.name},
                          {"kind", s.reference.kind},
                          {"method", s.reference.method},
                          {"cross_check", s.reference.cross_check},
                          {"error", s.reference.error},
                          {"component_errors", component_errors_json(s.reference)},
                          {"exact_rotation", s.reference.exact_rotation},
                          {"t_end", s.scene.t_end},
                          {"omega_scale", s.omega_scale},
                          {"inertia", inertia_json(s)},
                          {"r_feeds_back", s.problem.model().anisotropic()},
                          {"message", s.reference.message}});
  std::map<std::string, std::string> kind;
  for (const SweepScene& s : scenes) kind[s.scene.name] = s.reference.kind;
  ReferenceFloors floors;
  for (const SweepScene& s : scenes) floors[s.scene.name] = order_scale(s);
  json run_list = json::array();
  std::vector<FitRun> fit_input;
  for (const RunRecord& r : runs) {
    run_list.push_back(run_json(r, kind[r.scene]));
    fit_input.push_back(fit_run(r));
  }
  json options = options_of(spec);
  options["shard"] = {spec.shard_index, spec.shard_count};
  json report = {{"schema", kReportSchema},
                 {"created", utc_now()},
                 {"git", code_version()},
                 {"machine", machine()},
                 {"build", build()},
                 {"preset", spec.preset},
                 {"options", options},
                 {"references", references},
                 {"timed_call", timed_call(spec)},
                 {"runs", run_list},
                 {"stability", stability_json(stability)},
                 {"horizon", horizon_json(horizon)}};
  put_fits(report, fit_input, floors);
  if (spec.regime) {
    // the grid in the options too, so that shards of two grids refuse to merge
    report["options"]["regime"] = regime_axes_json(*spec.regime);
    std::vector<Scene> generated;
    for (const SweepScene& s : scenes) generated.push_back(s.scene);
    report["regime"] = regime_json(*spec.regime, generated);
  }
  return report;
}

json read_report(const std::string& path) {
  const json j = read_json_file(path, "report", "report");
  if (!j.is_object() || !j.contains("schema") || j["schema"] != kReportSchema)
    throw InputError("'" + path + "' is not a " + std::string(kReportSchema) + " report", "schema");
  return j;
}

namespace {

std::string joined(const std::vector<long>& numbers) {
  std::string text;
  for (const long n : numbers) text += (text.empty() ? "" : ", ") + std::to_string(n);
  return text;
}

// A merge needs every shard of the sweep once: a shard whose job failed is
// named, so that only it has to run again.
// A shard's "options.shard" [index, count], checked: whole numbers with
// 0 <= index < count, or an InputError naming the key and the file.
std::pair<long, long> shard_of(const json& report, const std::string& file) {
  const std::string key = "options.shard";
  const auto refuse = [&](const std::string& what) -> std::pair<long, long> {
    throw InputError("'" + file + "': " + what, key);
  };
  if (!report.contains("options") || !report["options"].is_object() || !report["options"].contains("shard"))
    return refuse("is missing");
  const json& shard = report["options"]["shard"];
  if (!shard.is_array() || shard.size() != 2 || !shard[0].is_number() || !shard[1].is_number())
    return refuse("must be [index, count], two whole numbers");
  const double index = shard[0].get<double>(), count = shard[1].get<double>();
  const bool whole = index == std::floor(index) && count == std::floor(count);
  if (!whole || !(count >= 1.0 && count <= 1e6) || !(index >= 0.0 && index < count))
    return refuse("must be [index, count], whole numbers with 0 <= index < count <= 1000000");
  return {static_cast<long>(index), static_cast<long>(count)};
}

void check_every_shard_once(const std::vector<json>& shards, const std::vector<std::string>& files) {
  const auto file_of = [&](std::size_t k) { return k < files.size() ? files[k] : "shard report " + std::to_string(k); };
  const long count = shard_of(shards.front(), file_of(0)).second;
  std::vector<long> have, missing;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const auto [index, of] = shard_of(shards[k], file_of(k));
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

}  // namespace

namespace {

// A shard's run: its entry as written, and what the fits read of it.
struct ShardRun {
  long index = 0;
  json entry;
  FitRun fit;
};

long index_of(const json& entry, const std::string& where) {
  if (!entry.is_object() || !entry.contains("index") || !entry["index"].is_number_integer())
    throw InputError(where + ".index is missing or not an integer", "reports");
  return entry["index"].get<long>();
}

const json& list_at(const json& report, const std::string& section, const std::string& key, const std::string& file) {
  const json* node = &report;
  for (const std::string& part : {section, key}) {
    if (part.empty()) continue;
    if (!node->is_object() || !node->contains(part))
      throw InputError("the report '" + file + "' has no key '" + (key.empty() ? section : section + "." + key) + "'",
                       "reports");
    node = &node->at(part);
  }
  if (!node->is_array())
    throw InputError("the report '" + file + "': '" + (key.empty() ? section : section + "." + key) + "' is not a list",
                     "reports");
  return *node;
}

}  // namespace

json merge_reports(const std::vector<json>& shards, const std::vector<std::string>& files) {
  if (shards.empty()) throw InputError("nothing to merge", "reports");
  check_every_shard_once(shards, files);
  json merged = shards.front();
  json base_options = merged.at("options");
  base_options.erase("shard");
  std::vector<ShardRun> runs;
  json drift = json::array(), stable = json::array(), references = json::array();
  json horizon = json::array();
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const json& s = shards[k];
    const std::string file = k < files.size() ? files[k] : "shard report " + std::to_string(k);
    json options = s.at("options");
    options.erase("shard");
    if (options != base_options)
      throw InputError("the reports come from different sweeps (their options differ)", "reports");
    const json& entries = list_at(s, "runs", "", file);
    const std::vector<FitRun> fits = fit_runs_of(entries, file);
    for (std::size_t i = 0; i < entries.size(); ++i)
      runs.push_back(
          {index_of(entries[i], "the report '" + file + "': runs[" + std::to_string(i) + "]"), entries[i], fits[i]});
    // entries sorted by their index below: each must have a number there
    const auto indexed = [&](const char* section, const char* list, json& into) {
      const json& items = list_at(s, section, list, file);
      for (std::size_t i = 0; i < items.size(); ++i) {
        if (!items[i].is_object() || !items[i].contains("index") || !items[i]["index"].is_number())
          throw InputError("the report '" + file + "': " + section + "." + list + "[" + std::to_string(i) +
                               "].index is missing or not a number",
                           "reports");
        into.push_back(items[i]);
      }
    };
    indexed("stability", "drift", drift);
    indexed("stability", "largest_stable_h", stable);
    if (s.contains("horizon")) indexed("horizon", "runs", horizon);  // absent from reports older than the study
    const json& refs = list_at(s, "references", "", file);
    for (std::size_t i = 0; i < refs.size(); ++i) {
      const json& r = refs[i];
      const std::string where = "the report '" + file + "': references[" + std::to_string(i) + "]";
      if (!r.is_object() || !r.contains("scene") || !r["scene"].is_string())
        throw InputError(where + ".scene is missing or not a string", "reports");
      // a reference's own error: null where it was not finite
      if (!r.contains("error") || !(r["error"].is_number() || r["error"].is_null()))
        throw InputError(where + ".error is missing or not a number or null", "reports");
      // omega's ceiling in the order fits
      if (!r.contains("omega_scale") || !r["omega_scale"].is_number())
        throw InputError(where + ".omega_scale is missing or not a number", "reports");
      // each component's floor in its order fit; absent from reports older than it
      if (r.contains("component_errors")) {
        const json& each = r["component_errors"];
        if (!each.is_object()) throw InputError(where + ".component_errors is not an object", "reports");
        for (const auto& [name, value] : each.items())
          if (!(value.is_number() || value.is_null()))
            throw InputError(where + ".component_errors." + name + " is not a number or null", "reports");
      }
      if (std::none_of(references.begin(), references.end(), [&](const json& x) { return x["scene"] == r["scene"]; }))
        references.push_back(r);
    }
  }
  auto by_index = [](const json& a, const json& b) { return a["index"].get<double>() < b["index"].get<double>(); };
  std::sort(runs.begin(), runs.end(), [](const ShardRun& a, const ShardRun& b) { return a.index < b.index; });
  std::sort(drift.begin(), drift.end(), by_index);
  std::sort(stable.begin(), stable.end(), by_index);
  std::sort(horizon.begin(), horizon.end(), by_index);
  mark_same_series(horizon);  // across the shards: a run's twin may be in another
  json run_list = json::array();
  std::vector<FitRun> fit_input;
  for (const ShardRun& r : runs) run_list.push_back(r.entry), fit_input.push_back(r.fit);
  // references in the order their scenes first appear in the sweep
  json ordered_refs = json::array();
  ReferenceFloors floors;
  for (const FitRun& r : fit_input)
    for (const json& ref : references)
      if (ref["scene"] == r.scene && std::none_of(ordered_refs.begin(), ordered_refs.end(),
                                                  [&](const json& x) { return x["scene"] == ref["scene"]; })) {
        ordered_refs.push_back(ref);
        floors[r.scene] = order_scale_of(ref);
      }
  merged["options"] = base_options;
  merged["options"]["shard"] = {0, 1};
  merged["references"] = ordered_refs;
  merged["runs"] = run_list;
  merged["stability"] = {{"drift", drift}, {"largest_stable_h", stable}};
  merged["horizon"] = {{"runs", horizon}};
  put_fits(merged, fit_input, floors);
  return merged;
}

std::string summary_table(const json& report) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-16s %-28s %9s %9s %10s %10s %s\n", "scene", "integrator", "order", "declared",
                "best worst", "its time", "failures");
  out << line;
  std::map<std::pair<std::string, std::string>, json> order_of;
  for (const json& o : report.at("orders"))
    order_of[{o.at("scene").get<std::string>(), o.at("integrator").get<std::string>()}] = o;
  std::vector<std::pair<std::string, std::string>> seen;
  for (const json& r : report.at("runs")) {
    const auto key = std::make_pair(r.at("scene").get<std::string>(), r.at("integrator").get<std::string>());
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    double best = kNaN, best_time = kNaN;
    int failures = 0;
    for (const json& x : report.at("runs")) {
      if (x.at("scene") != key.first || x.at("integrator") != key.second) continue;
      if (x.at("status") != "ok") ++failures;
      const double e = as_number(x.at("error").at("worst"));
      if (std::isfinite(e) && !(e >= best)) best = e, best_time = as_number(x.at("wall_s").at("median"));
    }
    const double observed = order_of.count(key) ? as_number(order_of[key].at("observed").at("contact")) : kNaN;
    // an adaptive method (no order fit) shows a dash, not nan
    char order[32] = "—";
    if (std::isfinite(observed)) std::snprintf(order, sizeof order, "%.2f", observed);
    std::snprintf(line, sizeof line, "%-16s %-28s %*s %9d %10.2e %10.2e %d\n", key.first.c_str(), key.second.c_str(),
                  std::isfinite(observed) ? 9 : 11, order, r.at("declared_order").get<int>(), best, best_time,
                  failures);
    out << line;
  }
  out << "order: the observed order of the contact point (— for adaptive methods or too few steps); best worst: "
         "the smallest worst error (ball radii or rad) over the method's runs; its time: that run's median wall "
         "time (s); failures: runs that did not reach t_end\n";
  return out.str();
}

}  // namespace rb

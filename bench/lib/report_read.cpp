// A report read back (merge, score --peers): every section it types is
// checked and parsed once, naming the file and the key of what does not
// read (docs/bad-input.md); the rest is carried through as it came.
#include <algorithm>
#include <cmath>

#include "bench/lib/entry_fields.hpp"
#include "bench/lib/report.hpp"
#include "bench/lib/report_parts.hpp"

namespace rb {

using json = nlohmann::json;

namespace {

std::string joined_key(const std::string& section, const std::string& key) {
  return key.empty() ? section : section + "." + key;
}

// report[section][key] (key empty: report[section]), a list, or an
// InputError naming the file and the key.
const json& list_at(const json& report, const std::string& section, const std::string& key, const std::string& file) {
  const json* node = &report;
  for (const std::string& part : {section, key}) {
    if (part.empty()) continue;
    if (!node->is_object() || !node->contains(part))
      throw InputError("the report '" + file + "' has no key '" + joined_key(section, key) + "'", "reports");
    node = &node->at(part);
  }
  if (!node->is_array())
    throw InputError("the report '" + file + "': '" + joined_key(section, key) + "' is not a list", "reports");
  return *node;
}

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

long index_of(const json& entry, const std::string& where) {
  if (!entry.is_object() || !entry.contains("index") || !entry["index"].is_number_integer())
    throw InputError(where + ".index is missing or not an integer", "reports");
  return entry["index"].get<long>();
}

std::vector<ReportRun> runs_of(const json& report, const std::string& file) {
  const json& entries = list_at(report, "runs", "", file);
  const std::vector<FitRun> fits = fit_runs_of(entries, file);
  std::vector<ReportRun> runs;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const json& e = entries[i];
    const long index = index_of(e, "the report '" + file + "': runs[" + std::to_string(i) + "]");
    // only the summary reads the time: a run without one shows nan there
    const bool timed = e.contains("wall_s") && e["wall_s"].is_object() && e["wall_s"].contains("median");
    runs.push_back({index, fits[i], timed ? report_parts::as_number(e["wall_s"]["median"]) : kNaN, e});
  }
  return runs;
}

// The stability and horizon records: merge sorts them by their index, so
// each must have a number there.
void check_indexed(const json& report, const char* section, const char* list, const std::string& file) {
  const json& items = list_at(report, section, list, file);
  for (std::size_t i = 0; i < items.size(); ++i)
    if (!items[i].is_object() || !items[i].contains("index") || !items[i]["index"].is_number())
      throw InputError("the report '" + file + "': " + section + "." + list + "[" + std::to_string(i) +
                           "].index is missing or not a number",
                       "reports");
}

std::vector<ReportReference> references_of(const json& report, const std::string& file) {
  const json& refs = list_at(report, "references", "", file);
  std::vector<ReportReference> out;
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
    out.push_back({r["scene"].get<std::string>(), order_scale_of(r), r});
  }
  return out;
}

// An order's fit as order_fit_json writes it (what it leaves out stays 0).
OrderFit order_fit_of(const EntryFields& f, const json& node, const std::string& path) {
  OrderFit fit;
  fit.points = static_cast<int>(f.integer(node, "points", path));
  fit.at_floor = static_cast<int>(f.integer(node, "at_plateau", path));
  fit.halving_slopes = f.numbers(node, "halving_slopes", path);
  fit.rung_slopes = f.numbers(node, "rung_slopes", path);
  fit.asymptotic = f.flag(node, "asymptotic", path);
  fit.all_at_plateau = f.flag(node, "all_at_plateau", path);
  // the trend test's; absent from reports older than it
  if (node.contains("trend_slopes")) {
    fit.trend_slopes = f.numbers(node, "trend_slopes", path);
    fit.trend = f.number_or_null(node, "trend", path);
    fit.trend_ci95 = f.number_or_null(node, "trend_ci95", path);
  }
  fit.slope = f.number_or_null(node, "slope", path);
  fit.slope_ci95 = f.number_or_null(node, "ci95", path);
  if (!std::isfinite(fit.slope)) return fit;
  fit.h_min = f.number_or_null(node, "h_min", path);
  fit.h_max = f.number_or_null(node, "h_max", path);
  fit.r2 = f.number_or_null(node, "r2", path);
  fit.residual = f.number_or_null(node, "residual", path);
  return fit;
}

// An "orders" entry; observed, ci95, fit and pass follow from the fits and
// verdicts, and are written from them again. components[i].declared (not
// in the report) stays 0.
ReportOrder order_of(const json& entry, const std::string& where) {
  const EntryFields f(entry, where);
  ReportOrder o;
  o.scene = f.text("scene");
  o.integrator = f.text("integrator");
  o.declared = static_cast<int>(f.integer("declared"));
  o.declared_rotation = static_cast<int>(f.integer("declared_rotation"));
  const json &fits = f.object(entry, "fits", ""), &self = f.object(entry, "self_convergence", "");
  const json &verdicts = f.object(entry, "verdict", ""), &reasons = f.object(entry, "inconclusive_reason", "");
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    const std::string c = kErrorComponents[i].name;
    ComponentOrder& component = o.components[i];
    component.reference = order_fit_of(f, f.object(fits, c, "fits."), "fits." + c + ".");
    component.self = order_fit_of(f, f.object(self, c, "self_convergence."), "self_convergence." + c + ".");
    component.judgement.verdict = f.text(verdicts, c, "verdict.");
    const json& reason = f.at(reasons, c, "inconclusive_reason.");
    if (!reason.is_null() && !reason.is_string()) f.refuse("inconclusive_reason." + c, "is not a string or null");
    if (reason.is_string()) component.judgement.reason = reason.get<std::string>();
  }
  return o;
}

LineFit line_fit_of(const EntryFields& f, const json& node, const std::string& path) {
  LineFit line;
  line.slope = f.number_or_null(node, "slope", path);
  line.slope_ci95 = f.number_or_null(node, "ci95", path);
  line.residual = f.number_or_null(node, "residual", path);
  line.points = static_cast<int>(f.integer(node, "points", path));
  return line;
}

ToleranceFit tolerance_fit_of(const json& entry, const std::string& where) {
  const EntryFields f(entry, where);
  ToleranceFit fit;
  fit.scene = f.text("scene");
  fit.integrator = f.text("integrator");
  fit.line = line_fit_of(f, entry, "");
  fit.line.intercept = f.number_or_null(entry, "intercept");
  fit.step = line_fit_of(f, f.object(entry, "step_order", ""), "step_order.");
  return fit;
}

}  // namespace

Report report_from_json(const json& j, const std::string& file) {
  Report report;
  report.shard = shard_of(j, file);
  report.options = j.at("options");
  report.options.erase("shard");
  report.runs = runs_of(j, file);
  check_indexed(j, "stability", "drift", file);
  check_indexed(j, "stability", "largest_stable_h", file);
  if (j.contains("horizon")) check_indexed(j, "horizon", "runs", file);  // absent from reports older than the study
  report.references = references_of(j, file);
  // derived from the runs: a merge fits them again, but what is there must read
  if (j.contains("orders")) {
    const json& orders = list_at(j, "orders", "", file);
    for (std::size_t i = 0; i < orders.size(); ++i)
      report.orders.push_back(order_of(orders[i], "the report '" + file + "': orders[" + std::to_string(i) + "]"));
  }
  if (j.contains("tolerance_fits")) {
    const json& fits = list_at(j, "tolerance_fits", "", file);
    for (std::size_t i = 0; i < fits.size(); ++i)
      report.tolerance_fits.push_back(
          tolerance_fit_of(fits[i], "the report '" + file + "': tolerance_fits[" + std::to_string(i) + "]"));
  }
  const auto carried = report_parts::carried_sections(report);
  for (const auto& [key, value] : carried) *value = j.contains(key) ? j.at(key) : json();
  const auto typed = report_parts::kTypedReportKeys;
  for (const auto& item : j.items()) {
    const std::string& key = item.key();  // not a structured binding: clang 14 cannot capture one
    if (std::none_of(typed.begin(), typed.end(), [&](const char* k) { return key == k; }) &&
        std::none_of(carried.begin(), carried.end(), [&](const auto& c) { return key == c.first; }))
      report.other[key] = item.value();
  }
  return report;
}

}  // namespace rb

// What a report derives from its runs: the observed orders of the
// fixed-step methods and the tolerance fits of the adaptive ones, fitted
// alike from a sweep's runs and from a merge's.
#include <cmath>
#include <map>

#include "bench/lib/report.hpp"
#include "bench/lib/report_parts.hpp"

namespace rb {

using json = nlohmann::json;
using report_parts::as_number;

namespace {

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

std::vector<ToleranceFit> fit_tolerances(const std::vector<FitRun>& runs) {
  const RunGroups groups = group_runs(runs, true);
  std::vector<ToleranceFit> fits;
  for (const RunKey& key : groups.keys) {
    std::vector<double> log_tol, log_error;
    for (const FitRun* r : groups.members.at(key)) {
      const double tol = r->rtol, e = r->error.worst;
      if (tol > 0.0 && e > 0.0) log_tol.push_back(std::log10(tol)), log_error.push_back(std::log10(e));
    }
    // the observed order of a method whose step it picks itself: the slope
    // of log error against log mean step, t_end / steps, over the same runs
    std::vector<double> log_step, log_step_error;
    for (const FitRun* r : groups.members.at(key)) {
      const double e = r->error.worst, steps = static_cast<double>(r->steps);
      const double t = r->stop_time;
      if (e > 0.0 && steps > 0.0 && t > 0.0)
        log_step.push_back(std::log10(t / steps)), log_step_error.push_back(std::log10(e));
    }
    fits.push_back({key.first, key.second, fit_line(log_tol, log_error), fit_line(log_step, log_step_error)});
  }
  return fits;
}

OrderScale order_scale_of(const json& reference) {
  const auto field = [&](const char* key) { return reference.contains(key) ? reference[key] : json(); };
  OrderScale scale{as_number(field("error")), as_number(field("omega_scale"))};
  if (!field("component_errors").is_object()) return scale;
  const json& each = reference["component_errors"];
  for (std::size_t i = 0; i < kErrorComponentCount; ++i)
    if (each.contains(kErrorComponents[i].name)) scale.component_floor[i] = as_number(each[kErrorComponents[i].name]);
  return scale;
}

std::vector<ReportOrder> fit_orders(const std::vector<FitRun>& runs, const ReferenceFloors& floors) {
  const RunGroups groups = group_runs(runs, false);
  std::vector<ReportOrder> orders;
  for (const RunKey& key : groups.keys) {
    const std::vector<const FitRun*>& group = groups.members.at(key);
    const FitRun& first = *group.front();
    const auto found = floors.find(key.first);
    orders.push_back({key.first, key.second, first.declared_order, first.declared_rotation_order,
                      group_orders(group, found != floors.end() ? found->second : OrderScale{})});
  }
  return orders;
}

json error_components_json() {
  json list = json::array();
  for (const ErrorComponent& c : kErrorComponents)
    list.push_back({{"name", c.name}, {"label", c.label}, {"unit", c.unit}, {"scale", scale_name(c.scale)}});
  return list;
}

}  // namespace rb

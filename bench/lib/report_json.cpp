// A Report as JSON (docs/formats.md): what is typed is written from its
// members, what is carried through as it came.
#include <algorithm>
#include <cmath>

#include "bench/lib/report.hpp"
#include "bench/lib/report_parts.hpp"

namespace rb {

using json = nlohmann::json;
using report_parts::number;

namespace {

// A fit as a report holds it: the slope with its 95 % interval and window,
// the halving and rung slopes, whether the halvings agree (asymptotic), the
// trend test's slopes and trend (null below 3 slopes), null where no slope
// was fitted.
json order_fit_json(const OrderFit& fit) {
  json j = {
      {"points", std::max(0, fit.points)}, {"at_plateau", fit.at_floor},   {"halving_slopes", fit.halving_slopes},
      {"rung_slopes", fit.rung_slopes},    {"asymptotic", fit.asymptotic}, {"all_at_plateau", fit.all_at_plateau},
      {"trend_slopes", fit.trend_slopes},  {"trend", number(fit.trend)},   {"trend_ci95", number(fit.trend_ci95)}};
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

json order_json(const ReportOrder& order) {
  json observed, ci95, fits, self, verdicts, reasons;
  // pass: every component as declared or exact, at least one as declared
  bool lower = false, all_as_declared = true, any_as_declared = false;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    const std::string c = kErrorComponents[i].name;
    const ComponentOrder& o = order.components[i];
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
  return {{"scene", order.scene},
          {"integrator", order.integrator},
          {"declared", order.declared},
          {"declared_rotation", order.declared_rotation},
          {"observed", observed},
          {"ci95", ci95},
          {"fit", fits[kErrorComponents[kHeadlineComponent].name]},
          {"fits", fits},
          {"self_convergence", self},
          {"plateau", {{"floor_multiple", kFloorMultiple}, {"rounding_step", kReferenceRoundingStep}}},
          {"verdict", verdicts},
          {"inconclusive_reason", reasons},
          {"pass", lower                                ? json(false)
                   : all_as_declared && any_as_declared ? json(true)
                                                        : json(nullptr)}};
}

json tolerance_fit_json(const ToleranceFit& fit) {
  const LineFit &line = fit.line, &step = fit.step;
  return {{"scene", fit.scene},
          {"integrator", fit.integrator},
          {"slope", number(line.slope)},
          {"intercept", number(line.intercept)},
          {"residual", number(line.residual)},
          {"ci95", number(line.slope_ci95)},
          {"points", line.points},
          {"step_order",
           {{"slope", number(step.slope)},
            {"ci95", number(step.slope_ci95)},
            {"residual", number(step.residual)},
            {"points", step.points}}}};
}

}  // namespace

json orders_json(const std::vector<ReportOrder>& orders) {
  json list = json::array();
  for (const ReportOrder& o : orders) list.push_back(order_json(o));
  return list;
}

json tolerance_fits_json(const std::vector<ToleranceFit>& fits) {
  json list = json::array();
  for (const ToleranceFit& fit : fits) list.push_back(tolerance_fit_json(fit));
  return list;
}

void to_json(json& j, const Report& report) {
  j = report.other;
  json options = report.options;
  options["shard"] = {report.shard.first, report.shard.second};
  json references = json::array(), runs = json::array();
  for (const ReportReference& r : report.references) references.push_back(r.entry);
  for (const ReportRun& r : report.runs) runs.push_back(r.entry);
  j["options"] = options;
  j["references"] = references;
  j["runs"] = runs;
  j["error_components"] = error_components_json();
  j["orders"] = orders_json(report.orders);
  j["tolerance_fits"] = tolerance_fits_json(report.tolerance_fits);
  for (const auto& [key, value] : report_parts::carried_sections(report))
    if (!value->is_null()) j[key] = *value;
}

json to_json(const Report& report) {
  json j;
  to_json(j, report);
  return j;
}

}  // namespace rb

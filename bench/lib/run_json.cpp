// The report's records as JSON: a run's entry with its errors, a scene's
// reference entry, and the stability study's records (docs/formats.md).
#include <algorithm>
#include <cmath>

#include "bench/lib/report.hpp"
#include "bench/lib/report_parts.hpp"
#include "problems/utf8.hpp"

namespace rb {

using json = nlohmann::json;
using report_parts::number;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

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

// What an implicit method pays besides F, that rhs_equivalents counts in
// (integrators/integrator.hpp); null for a method without a Jacobian.
json implicit_cost_json(const Cost& c, bool needs_jacobian) {
  if (!needs_jacobian) return nullptr;
  return {{"jacobian_columns", c.jacobian_columns},
          {"model_passes", c.model_passes},
          {"lu_decompositions", c.lu_decompositions},
          {"linear_algebra_flops", c.linear_algebra_flops},
          {"flops_per_rhs", kFlopsPerRhs}};
}

json growth_json(const GrowthShape& g) {
  return {{"p_early", number(g.p_early)}, {"p_late", number(g.p_late)}, {"exponential", g.exponential}};
}

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

// One rung's verdict at one horizon.
json horizon_verdict_json(const HorizonVerdict& v) {
  return {
      {"horizon", v.horizon},
      {"crossed_at", number(v.crossed_at)},
      {"failed_at", number(v.failed_at)},
      {"energy_error", number(v.energy_error_flat)},
      {"energy_error_on_group", number(v.energy_error)},
      {"rotation_defect", number(v.rotation_defect)},
      {"growth", {{"energy_error", growth_json(v.energy_growth)}, {"rotation_defect", growth_json(v.defect_growth)}}},
      {"blow_up", v.blow_up == BlowUp::none ? json(nullptr) : json(blow_up_name(v.blow_up))},
      {"within", v.within()}};
}

// A rung's failure at the last horizon it was judged at (null: stable):
// how it blew up, else the first drift bound it crossed.
json rung_failure(const StableStepTry& t) {
  if (t.stable || t.at.empty()) return nullptr;
  if (t.last().blow_up != BlowUp::none) return blow_up_name(t.last().blow_up);
  const double e = t.energy_crossed_at, q = t.defect_crossed_at;
  if (!std::isnan(e) && !(q < e)) return kEnergyQuantity;
  if (!std::isnan(q)) return kDefectQuantity;
  return nullptr;
}

json stable_step_json(const StableStepRecord& r) {
  json tried = json::array();
  for (const StableStepTry& t : r.tried) {
    json at = json::array();
    for (const HorizonVerdict& v : t.at) at.push_back(horizon_verdict_json(v));
    const HorizonVerdict last = t.at.empty() ? HorizonVerdict{} : t.last();
    tried.push_back(
        {{"h", t.h},
         {"status", std::string(status_name(t.status))},
         {"message", t.message},
         {"stop_time", t.stop_time},
         {"cut_short", t.cut_short},
         {"steps", t.steps},
         {"energy_error", number(last.energy_error_flat)},
         {"energy_error_on_group", number(last.energy_error)},
         {"rotation_defect", number(last.rotation_defect)},
         {"growth",
          {{"energy_error", growth_json(last.energy_growth)}, {"rotation_defect", growth_json(last.defect_growth)}}},
         {"crossed_at",
          {{kEnergyQuantity, number(t.energy_crossed_at)},
           {kDefectQuantity, number(t.defect_crossed_at)},
           {"energy-blow-up", number(t.energy_blown_at)},
           {"defect-blow-up", number(t.defect_blown_at)}}},
         {"horizons", at},
         {"failure", rung_failure(t)},
         {"stable", t.stable}});
  }
  json blow_up = json::array(), drift_limited = json::array();
  for (const BlowUpStep& b : r.blow_up)
    blow_up.push_back({{"horizon", b.horizon},
                       {"h", number(b.h)},
                       {"cause", std::isnan(b.h) ? json(nullptr) : json(blow_up_name(b.cause))},
                       {"status", std::isnan(b.h) ? json(nullptr) : json(std::string(status_name(b.status)))},
                       {"smallest_tried", b.smallest_tried}});
  for (const DriftLimit& d : r.drift_limited)
    drift_limited.push_back(
        {{"horizon", d.horizon},
         {"h", number(d.h)},
         {"at_limit", d.at_limit},
         {"next_h", number(d.next_h)},
         {"limited_by", d.limited_by.empty() ? json(nullptr) : json(d.limited_by)},
         {"blow_up", d.blow_up == BlowUp::none ? json(nullptr) : json(blow_up_name(d.blow_up))},
         {"status", std::isnan(d.next_h) ? json(nullptr) : json(std::string(status_name(d.next_status)))},
         {"value", number(d.value)},
         {"bound", number(d.bound)}});
  return {{"index", r.index},
          {"scene", r.scene},
          {"integrator", r.method.name},
          {"family", r.method.family},
          {"h", number(r.h)},
          {"horizon", r.horizon},
          {"horizons", r.horizons},
          {"at_limit", r.at_limit},
          {"energy_error", number(r.energy_error)},
          {"energy_error_on_group", number(r.energy_error_on_group)},
          {"rotation_defect", number(r.rotation_defect)},
          {"energy_scale", r.energy_scale},
          {"thresholds", report_parts::bounds_json(r.bounds)},
          {"blow_up", {{"same_at_every_horizon", !r.blow_up_moves}, {"at", blow_up}}},
          {"drift_limited", drift_limited},
          {"tried", tried}};
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
      {"rhs_equivalents", number(r.cost.rhs_equivalents())},
      {"implicit_cost", implicit_cost_json(r.cost, m.needs_jacobian)},
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
      {"drift",
       {{"energy", number(r.energy_drift)},
        {"energy_on_group", number(r.energy_drift_on_group)},
        {"rotation_defect", number(r.rotation_drift)}}},
      {"final",
       {{"t", r.stop_time},
        {"contact", {r.final_state[kOffsetAlpha], r.final_state[kOffsetAlpha + 1]}},
        {"centre",
         {number(r.final_point.centre.x()), number(r.final_point.centre.y()), number(r.final_point.centre.z())}},
        {"omega", {number(r.final_point.omega.x()), number(r.final_point.omega.y()), number(r.final_point.omega.z())}},
        {"R", {{R(0, 0), R(0, 1), R(0, 2)}, {R(1, 0), R(1, 1), R(1, 2)}, {R(2, 0), R(2, 1), R(2, 2)}}}}}};
}

namespace report_parts {

json reference_json(const SweepScene& s) {
  return {{"scene", s.scene.name},
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
          {"message", s.reference.message}};
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
                     {"energy_error_on_group", d.energy_error_on_group},
                     {"rotation_defect", d.rotation_defect},
                     {"steps", d.cost.steps},
                     {"rhs_evals", d.cost.rhs_evals},
                     {"rhs_equivalents", number(d.cost.rhs_equivalents())},
                     {"wall_s", d.wall_s}});
  for (const StableStepRecord& r : s.largest_stable_h) stable.push_back(stable_step_json(r));
  return {{"drift", drift}, {"largest_stable_h", stable}};
}

}  // namespace report_parts

}  // namespace rb

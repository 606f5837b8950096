#include "bench/lib/fit_run.hpp"

#include <cmath>
#include <utility>

#include "bench/lib/entry_fields.hpp"
#include "problems/input_error.hpp"

namespace rb {

using json = nlohmann::json;

namespace {

// A number as the report holds it: not finite is null, and null reads NaN.
double as_reported(double v) { return std::isfinite(v) ? v : kNaN; }

FitRun fit_run_of(const json& run, const std::string& where) {
  const EntryFields f(run, where);
  FitRun r;
  r.scene = f.text("scene");
  r.integrator = f.text("integrator");
  r.adaptive = f.flag("adaptive");
  r.declared_order = static_cast<int>(f.integer("declared_order"));
  r.declared_rotation_order = static_cast<int>(f.integer("declared_rotation_order"));
  r.h = f.number_or_null(run, "h");
  r.rtol = f.number_or_null(run, "rtol");
  r.stop_time = f.number_or_null(run, "stop_time");
  r.steps = f.integer("steps");
  r.error = f.errors("error");
  r.ok = f.text("status") == "ok";
  r.end = f.end_point();
  return r;
}

}  // namespace

FitRun fit_run(const RunRecord& record) {
  FitRun r;
  r.scene = record.scene;
  r.integrator = record.method.name;
  r.adaptive = record.method.adaptive;
  r.declared_order = record.method.declared_order;
  r.declared_rotation_order = record.method.rotation_order;
  r.h = as_reported(record.h);
  r.rtol = as_reported(record.rtol);
  r.stop_time = as_reported(record.stop_time);
  r.steps = record.cost.steps;
  r.error.below_floor = record.error.below_floor;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) r.error.component(i) = as_reported(record.error.component(i));
  r.error.worst = as_reported(record.error.worst);
  r.ok = record.status == Status::ok;
  r.end = record.final_point;
  return r;
}

std::vector<FitRun> fit_runs_of(const json& runs, const std::string& file) {
  const std::string where = "the report '" + file + "': runs";
  if (!runs.is_array()) throw InputError(where + " is not a list", "reports");
  std::vector<FitRun> out;
  for (std::size_t i = 0; i < runs.size(); ++i)
    out.push_back(fit_run_of(runs[i], where + "[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace rb

#include "bench/lib/fit_run.hpp"

#include <cmath>
#include <utility>

#include "problems/input_error.hpp"

namespace rb {

using json = nlohmann::json;

namespace {

// A number as the report holds it: not finite is null, and null reads NaN.
double as_reported(double v) { return std::isfinite(v) ? v : kNaN; }

// Reads the fields of one run entry the fits need; where names it in
// errors: "the report 'FILE': runs[i]".
class RunFields {
 public:
  RunFields(const json& run, std::string where) : run_(run), where_(std::move(where)) {
    if (!run.is_object()) refuse("", "is not an object");
  }

  const json& at(const json& node, const std::string& key, const std::string& path) const {
    if (!node.is_object() || !node.contains(key)) refuse(path + key, "is missing");
    return node.at(key);
  }
  std::string text(const std::string& key) const {
    const json& v = at(run_, key, "");
    if (!v.is_string()) refuse(key, "is not a string");
    return v.get<std::string>();
  }
  bool flag(const std::string& key) const {
    const json& v = at(run_, key, "");
    if (!v.is_boolean()) refuse(key, "is not true or false");
    return v.get<bool>();
  }
  long integer(const std::string& key) const {
    const json& v = at(run_, key, "");
    if (!v.is_number_integer()) refuse(key, "is not an integer");
    return v.get<long>();
  }
  // a number or null (NaN)
  double number_or_null(const json& node, const std::string& key, const std::string& path = "") const {
    const json& v = at(node, key, path);
    if (v.is_null()) return kNaN;
    if (!v.is_number()) refuse(path + key, "is not a number or null");
    return v.get<double>();
  }
  RunErrors errors(const std::string& key) const {
    const json& e = at(run_, key, "");
    if (!e.is_object()) refuse(key, "is not an object");
    const std::string path = key + ".";
    RunErrors out;
    for (std::size_t i = 0; i < kErrorComponentCount; ++i)
      out.component(i) = number_or_null(e, kErrorComponents[i].name, path);
    out.worst = number_or_null(e, "worst", path);
    const json& below = at(e, "below_floor", path);
    if (!below.is_array()) refuse(path + "below_floor", "is not a list");
    for (const json& name : below) {
      if (!name.is_string()) refuse(path + "below_floor", "holds something that is not a string");
      out.below_floor.push_back(name.get<std::string>());
    }
    return out;
  }
  // "final": contact, centre, omega and R (NaN where null)
  ReferencePoint end_point() const {
    const json& e = at(run_, "final", "");
    if (!e.is_object()) refuse("final", "is not an object");
    ReferencePoint p;
    const auto vector = [&](const char* key, auto& out) {
      const json& v = at(e, key, "final.");
      const std::string path = std::string("final.") + key;
      if (!v.is_array() || v.size() != static_cast<std::size_t>(out.size()))
        refuse(path, "is not a list of " + std::to_string(out.size()) + " numbers");
      for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<Eigen::Index>(i)] = entry(v[i], path);
    };
    vector("contact", p.alpha);
    vector("centre", p.centre);
    vector("omega", p.omega);
    const json& R = at(e, "R", "final.");
    if (!R.is_array() || R.size() != 3) refuse("final.R", "is not 3 rows of 3 numbers");
    for (std::size_t i = 0; i < 3; ++i) {
      if (!R[i].is_array() || R[i].size() != 3) refuse("final.R", "is not 3 rows of 3 numbers");
      for (std::size_t j = 0; j < 3; ++j)
        p.R(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = entry(R[i][j], "final.R");
    }
    return p;
  }
  double entry(const json& v, const std::string& path) const {
    if (v.is_null()) return kNaN;
    if (!v.is_number()) refuse(path, "holds something that is not a number or null");
    return v.get<double>();
  }
  [[noreturn]] void refuse(const std::string& key, const std::string& problem) const {
    throw InputError(where_ + (key.empty() ? "" : "." + key) + " " + problem, "reports");
  }

 private:
  const json& run_;
  std::string where_;
};

FitRun fit_run_of(const json& run, const std::string& where) {
  const RunFields f(run, where);
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

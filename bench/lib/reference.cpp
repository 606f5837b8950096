#include "bench/lib/reference.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/lib/output_file.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

// Bumped when the physics or the reference procedure changes, so that stale
// cache entries are never read.
constexpr int kReferenceFormat = 1;

std::vector<ReferencePoint> solve(const Problem& problem, const std::string& method, double h,
                                  const std::vector<double>& times) {
  RunOptions options;
  options.t_end = times.back();
  options.h = h;
  options.output_times = times;
  const RunResult run = find_integrator(method).integrate(problem, options);
  if (run.status != Status::ok)
    throw InputError("the reference method " + method + " stopped at t = " + std::to_string(run.stop_time) + " (" +
                         std::string(status_name(run.status)) + ": " + run.message +
                         "); the scene is not fit for a benchmark",
                     problem.name());
  std::vector<ReferencePoint> points;
  for (const FlatState& y : run.output.y) points.push_back(reference_point_of(problem, y));
  return points;
}

std::string cache_key(const std::string& scene_content, const std::vector<double>& times, const ReferenceSettings& s) {
  std::ostringstream key;
  key.precision(17);
  key << kReferenceFormat << '|' << code_version() << '|' << s.primary << '|' << s.cross_check << '|' << s.h << '|'
      << scene_content << '|';
  for (double t : times) key << t << ',';
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016zx", std::hash<std::string>{}(key.str()));
  return hex;
}

nlohmann::json to_json(const Reference& r) {
  nlohmann::json j = {{"scene", r.scene},
                      {"kind", r.kind},
                      {"message", r.message},
                      {"method", r.method},
                      {"cross_check", r.cross_check},
                      {"error", r.error},
                      {"exact_rotation", r.exact_rotation},
                      {"t", r.t}};
  nlohmann::json points = nlohmann::json::array();
  for (const ReferencePoint& p : r.points) {
    std::vector<double> v{p.alpha.x(), p.alpha.y()};
    for (int i = 0; i < 3; ++i) v.push_back(p.centre[i]);
    for (int i = 0; i < 3; ++i) v.push_back(p.omega[i]);
    for (int i = 0; i < 9; ++i) v.push_back(p.R(i / 3, i % 3));
    points.push_back(v);
  }
  j["points"] = points;
  return j;
}

Reference from_json(const nlohmann::json& j) {
  Reference r;
  r.scene = j.at("scene");
  r.kind = j.at("kind");
  r.message = j.at("message");
  r.method = j.at("method");
  r.cross_check = j.at("cross_check");
  r.error = j.at("error");
  r.exact_rotation = j.at("exact_rotation");
  r.t = j.at("t").get<std::vector<double>>();
  for (const auto& row : j.at("points")) {
    const std::vector<double> v = row.get<std::vector<double>>();
    ReferencePoint p;
    p.alpha = Vec2(v.at(0), v.at(1));
    p.centre = Vec3(v.at(2), v.at(3), v.at(4));
    p.omega = Vec3(v.at(5), v.at(6), v.at(7));
    for (int i = 0; i < 9; ++i) p.R(i / 3, i % 3) = v.at(static_cast<std::size_t>(8 + i));
    r.points.push_back(p);
  }
  return r;
}

}  // namespace

ReferencePoint reference_point_of(const Problem& problem, const FlatState& y) {
  const Derived d = problem.model().derived(y);
  return {contact_of(y), d.centre, d.omega, rotation_of(y)};
}

double point_distance(const ReferencePoint& a, const ReferencePoint& b) {
  return std::max({(a.alpha - b.alpha).norm(), (a.centre - b.centre).norm(), (a.omega - b.omega).norm(),
                   rotation_angle_between(a.R, b.R)});
}

std::string code_version() {
  static const std::string version = [] {
    std::string out;
    if (FILE* pipe = popen("git -C \"" RB_SOURCE_DIR "\" rev-parse HEAD 2>/dev/null", "r")) {
      char buffer[128];
      while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
      pclose(pipe);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    return out.empty() ? std::string("unknown") : out;
  }();
  return version;
}

Reference make_reference(const Problem& problem, const std::string& scene_content, const std::vector<double>& times,
                         const ReferenceSettings& settings) {
  namespace fs = std::filesystem;
  fs::path cache_file;
  if (!settings.cache_dir.empty()) {
    cache_file =
        fs::path(settings.cache_dir) / (problem.name() + "-" + cache_key(scene_content, times, settings) + ".json");
    std::ifstream in(cache_file);
    if (in) {
      try {
        Reference cached = from_json(nlohmann::json::parse(in));
        cached.from_cache = true;
        return cached;
      } catch (const std::exception&) {
        // a damaged cache entry is recomputed and overwritten
      }
    }
  }

  Reference ref;
  ref.scene = problem.name();
  ref.t = times;
  std::vector<ReferencePoint> check;
  try {
    ref.points = solve(problem, settings.primary, settings.h, times);
    check = solve(problem, settings.cross_check, settings.h / 2, times);
  } catch (const InputError& e) {
    ref.kind = "none";
    ref.points.clear();
    ref.message = e.message();
    return ref;
  }
  std::ostringstream name;
  name.precision(6);
  name << settings.primary << " h=" << settings.h;
  ref.method = name.str();
  name.str("");
  name << settings.cross_check << " h=" << settings.h / 2;
  ref.cross_check = name.str();
  ref.kind = "computed";
  for (std::size_t i = 0; i < times.size(); ++i)
    ref.error = std::max(ref.error, point_distance(ref.points[i], check[i]));

  if (const ExactSolution* exact = problem.exact()) {
    // the closed form replaces what it knows; the computed solution checks it
    ref.kind = "exact";
    ref.cross_check = ref.method;
    ref.method = "exact " + exact->name();
    ref.exact_rotation = false;
    double disagreement = 0.0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const ExactState e = exact->at(times[i]);
      FlatState y = make_flat(e.has_rotation ? e.R : ref.points[i].R, Vec3::Zero(), e.alpha);
      const Vec3 N = problem.model().normal_at(e.alpha.x(), e.alpha.y());
      y.segment<3>(kOffsetV) = problem.model().momentum_from_omega(e.R, N, e.omega);
      const ReferencePoint p = reference_point_of(problem, y);
      disagreement = std::max(disagreement, point_distance(p, ref.points[i]));
      ref.points[i] = p;
      ref.exact_rotation = e.has_rotation;
    }
    ref.error = disagreement;
  }

  if (!cache_file.empty()) {
    std::error_code ec;
    fs::create_directories(cache_file.parent_path(), ec);
    // whole or not at all, also when shards write the same entry at once;
    // a cache that cannot be written is only slower next time
    try {
      write_output_file(cache_file.string(),
                        to_json(ref).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), "cache");
    } catch (const InputError&) {
    }
  }
  return ref;
}

}  // namespace rb

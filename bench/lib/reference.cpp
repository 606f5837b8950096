#include "bench/lib/reference.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/lib/json_input.hpp"
#include "bench/lib/output_file.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/safe_path.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

// Bumped when the physics or the reference procedure changes, so that stale
// cache entries are never read.
constexpr int kReferenceFormat = 2;

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

// Raises ref's own error, overall and per component, to the distance of a and b.
void largest_distances(Reference& ref, const ReferencePoint& a, const ReferencePoint& b) {
  const std::array<double, kErrorComponentCount> d = component_distances(a, b);
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    ref.component_error[i] = std::max(ref.component_error[i], d[i]);
    ref.error = std::max(ref.error, d[i]);
  }
}

std::string sha256_hex(const std::string& text) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  EVP_Digest(text.data(), text.size(), digest, &size, EVP_sha256(), nullptr);
  std::string hex;
  char byte[3];
  for (unsigned int i = 0; i < size; ++i) std::snprintf(byte, sizeof byte, "%02x", digest[i]), hex += byte;
  return hex;
}

// What an entry is made from: the one list a cached entry must match field
// for field. Every setting of the reference is in it (ReferenceSettings
// whole, but the folder), so a new setting there must be added here.
nlohmann::json made_from(const std::string& scene_content, const std::vector<double>& times,
                         const ReferenceSettings& s) {
  return {{"format", kReferenceFormat},
          {"code_version", code_version()},
          {"scene_sha256", sha256_hex(scene_content)},
          {"primary", s.primary},
          {"cross_check", s.cross_check},
          {"h", s.h},
          {"times", times}};
}

// Why a cached entry cannot be used, or "" when it can.
std::string entry_problem(const nlohmann::json& j, const nlohmann::json& expected, const std::vector<double>& times) {
  if (!j.is_object() || !j.contains("made_from") || !j.contains("checksum") || !j.contains("reference"))
    return "not a cache entry";
  if (j["made_from"] != expected) return "made from another scene, grid, method or code version";
  if (!j["checksum"].is_string() || j["checksum"] != cache_entry_checksum(j)) return "checksum differs";
  const nlohmann::json& r = j["reference"];
  if (!r.is_object() || !r.contains("kind") || !r.contains("t") || !r.contains("points")) return "fields missing";
  if (r["t"] != nlohmann::json(times)) return "another output grid";
  const bool none = r["kind"] == "none";
  if (!none && r["kind"] != "exact" && r["kind"] != "computed") return "unknown kind";
  const nlohmann::json& points = r["points"];
  if (!points.is_array() || points.size() != (none ? 0 : times.size()))
    return "holds " + std::to_string(points.is_array() ? points.size() : 0) + " points for " +
           std::to_string(times.size()) + " output times";
  for (const nlohmann::json& row : points) {
    if (!row.is_array() || row.size() != 17) return "a point without its 17 numbers";
    for (const nlohmann::json& v : row)
      if (!v.is_number() || !std::isfinite(v.get<double>())) return "a point with a value that is not finite";
    // the checksum holds no secret, so a forged entry can carry a right one: its content must still be a
    // reference, its R a rotation (a zeroed point is not)
    Mat3 R;
    for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = row[static_cast<std::size_t>(8 + i)].get<double>();
    if (rotation_defect(R) > 1e-8 || R.determinant() <= 0.0) return "a point whose R is not a rotation";
  }
  if (!r.contains("error") || !r["error"].is_number() || !(r["error"].get<double>() >= 0.0))
    return "no finite own error";
  const nlohmann::json& each = r.contains("component_errors") ? r["component_errors"] : nlohmann::json();
  if (!each.is_array() || each.size() != kErrorComponentCount) return "no own error per component";
  for (const nlohmann::json& v : each)
    if (!v.is_number() || !(v.get<double>() >= 0.0)) return "an own error per component that is not finite";
  return "";
}

nlohmann::json to_json(const Reference& r) {
  nlohmann::json j = {{"scene", r.scene},
                      {"kind", r.kind},
                      {"message", r.message},
                      {"method", r.method},
                      {"cross_check", r.cross_check},
                      {"error", r.error},
                      {"component_errors", r.component_error},
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
  r.component_error = j.at("component_errors").get<std::array<double, kErrorComponentCount>>();
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

// The cache folder made (as mkdir -p) by the path rule
// (problems/safe_path.hpp): false, with a note, when a link on the way is
// another user's; a folder that cannot be made or written is only not
// cached into, as before.
bool usable_cache_folder(const std::string& cache_dir) {
  const OpenedFolder folder = open_folder(cache_dir, MissingFolders::make);
  if (folder || folder.refused.empty()) return true;
  std::fprintf(stderr, "rollbench: note: the cache folder '%s' is not used (%s)\n", cache_dir.c_str(),
               folder.refused.c_str());
  return false;
}

}  // namespace

void check_cache_folder(const std::string& cache_dir) {
  if (cache_dir.empty()) return;
  if (const OpenedFolder folder = open_folder(cache_dir, MissingFolders::make); !folder && !folder.refused.empty())
    throw InputError("cannot use the cache folder '" + cache_dir + "' (" + folder.refused + ")", "cache");
}

std::string cache_entry_checksum(const nlohmann::json& entry) {
  return sha256_hex(entry["reference"].dump() + entry["made_from"].dump());
}

ReferencePoint reference_point_of(const Problem& problem, const FlatState& y) {
  const Derived d = problem.model().derived(y);
  return {contact_of(y), d.centre, d.omega, rotation_of(y)};
}

std::array<double, kErrorComponentCount> component_distances(const ReferencePoint& a, const ReferencePoint& b) {
  return {(a.alpha - b.alpha).norm(), (a.centre - b.centre).norm(), (a.omega - b.omega).norm(),
          rotation_angle_between(a.R, b.R)};
}

double point_distance(const ReferencePoint& a, const ReferencePoint& b) {
  const auto d = component_distances(a, b);
  return *std::max_element(d.begin(), d.end());
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
  nlohmann::json key;
  if (!settings.cache_dir.empty() && usable_cache_folder(settings.cache_dir)) {
    key = made_from(scene_content, times, settings);
    // the file's name is a hash of what it is made from: never the scene's name
    cache_file = fs::path(settings.cache_dir) / ("reference-" + sha256_hex(key.dump()).substr(0, 32) + ".json");
    std::error_code ec;
    if (fs::exists(cache_file, ec)) {
      std::string why;
      try {
        // its size checked before it is read: a 1 GiB entry costs nothing
        const nlohmann::json entry = read_json_file(cache_file.string(), reference_cache_input(times.size()), "cache");
        why = entry_problem(entry, key, times);
        if (why.empty()) {
          Reference cached = from_json(entry["reference"]);
          cached.from_cache = true;
          return cached;
        }
      } catch (const InputError& e) {
        why = e.message();
      } catch (const std::exception& e) {
        why = e.what();
      }
      // never trusted: a damaged or foreign entry is recomputed and replaced
      std::fprintf(stderr, "rollbench: note: the cached reference '%s' of scene %s is not used (%s); recomputing\n",
                   cache_file.c_str(), problem.name().c_str(), why.c_str());
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
  for (std::size_t i = 0; i < times.size(); ++i) largest_distances(ref, ref.points[i], check[i]);

  if (const ExactSolution* exact = problem.exact()) {
    // the closed form replaces what it knows; the computed solution checks it
    ref.kind = "exact";
    ref.cross_check = ref.method;
    ref.method = "exact " + exact->name();
    ref.exact_rotation = false;
    const std::array<double, kErrorComponentCount> computed = ref.component_error;
    ref.error = 0.0;
    ref.component_error.fill(0.0);
    for (std::size_t i = 0; i < times.size(); ++i) {
      const ExactState e = exact->at(times[i]);
      FlatState y = make_flat(e.has_rotation ? e.R : ref.points[i].R, Vec3::Zero(), e.alpha);
      const Vec3 N = problem.model().normal_at(e.alpha.x(), e.alpha.y());
      y.segment<3>(kOffsetV) = problem.model().momentum_from_omega(e.R, N, e.omega);
      const ReferencePoint p = reference_point_of(problem, y);
      largest_distances(ref, p, ref.points[i]);
      ref.points[i] = p;
      ref.exact_rotation = e.has_rotation;
    }
    // a rotation the closed form does not know is the computed one's, with its error
    for (std::size_t c = 0; c < kErrorComponentCount; ++c)
      if (!ref.exact_rotation && std::string(kErrorComponents[c].name) == "rotation")
        ref.component_error[c] = computed[c];
  }

  if (!cache_file.empty()) {
    // whole or not at all, also when shards write the same entry at once;
    // a cache that cannot be written is only slower next time
    try {
      nlohmann::json entry = {{"made_from", key}, {"reference", to_json(ref)}};
      // the checksum over the text as it is read back (dump is canonical)
      entry["reference"] =
          nlohmann::json::parse(entry["reference"].dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
      entry["checksum"] = cache_entry_checksum(entry);
      write_output_file(cache_file.string(), entry.dump(), "cache");
    } catch (const InputError&) {
    }
  }
  return ref;
}

}  // namespace rb

#pragma once
// Reference solutions: what every run's error is measured against.
//
// Every scene gets a computed reference: a high-accuracy solution from one
// method, cross-checked by a second, different one; their largest
// disagreement is the reference's own error (its floor: an error below it is
// not a measurement). Where the scene has a closed form, the exact solution
// replaces the computed one for every component it knows, and the computed
// one checks it. References are cached on disk, keyed by the scene file's
// content, the output grid and the code version.
#include <array>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "bench/lib/error_components.hpp"
#include "integrators/integrator.hpp"

namespace rb {

// The state of the reference at one output time, in the components errors
// are measured in.
struct ReferencePoint {
  Vec2 alpha;
  Vec3 centre;
  Vec3 omega;
  Mat3 R;
};

struct Reference {
  std::string scene;
  std::string kind;         // "exact", "computed", or "none" when a reference method failed
  std::string method;       // e.g. "rkmk4 h=0.000244140625" or "exact plane"
  std::string cross_check;  // the second method
  double error = 0.0;       // largest disagreement, contact/centre/omega/rotation
  // the largest disagreement in each error component (kErrorComponents),
  // each in its own unit: the floor of that component's order fit (ω, in
  // rad/s of a scene whose |ω| reaches 38, has a floor far above the
  // contact point's, in m)
  std::array<double, kErrorComponentCount> component_error{};
  bool exact_rotation = true;  // false: the rotation comes from the computed solution
  std::vector<double> t;
  std::vector<ReferencePoint> points;
  std::string message;  // why there is no reference ("none")
  bool from_cache = false;
};

// Which methods and settings make references: defaults in one place.
struct ReferenceSettings {
  // order 8 on both sides, a Lie method and a flat one of another code: a
  // floor near rounding, far below the smallest error in any fit window
  std::string primary = "rkmk8";
  std::string cross_check = "odeint-fehlberg78";
  double h = 1.0 / 1024.0;  // the primary's step; the cross-check takes h / 2
  std::string cache_dir;    // empty: no caching
};

// The reference of a problem on an output grid (increasing, ending at the
// problem's t_end). When a reference method fails on the scene (a scene
// built to fail), the reference has kind "none", no points, and says why:
// the scene's runs are still made and recorded, without errors.
// scene_content: the scene file's text (the cache key).
Reference make_reference(const Problem& problem, const std::string& scene_content, const std::vector<double>& times,
                         const ReferenceSettings& settings);

// Makes the cache folder (as mkdir -p) by the path rule of
// problems/safe_path.hpp, before any work: InputError under "cache"
// ("cannot use the cache folder 'D' ('L' is a symbolic link owned by uid N
// in a folder owned by uid M; not followed)") when a link on the way is
// another user's. Nothing for "" (no cache); a folder that cannot be made
// or written is only not cached into (make_reference).
void check_cache_folder(const std::string& cache_dir);

// The reference point of a state (derived quantities of the model).
ReferencePoint reference_point_of(const Problem& problem, const FlatState& y);

// Largest disagreement of two points over the four components.
double point_distance(const ReferencePoint& a, const ReferencePoint& b);

// The distance of two points in each error component, in the order of
// kErrorComponents: contact, centre and omega by the Euclidean norm, the
// rotation by the angle of a^T b (what every error is measured in).
std::array<double, kErrorComponentCount> component_distances(const ReferencePoint& a, const ReferencePoint& b);

// A cache entry's checksum: SHA-256 over its reference and what it is made
// from. It holds no secret: it finds damage, and the content checks find forgeries.
std::string cache_entry_checksum(const nlohmann::json& entry);

// The commit of the source tree, or "unknown".
std::string code_version();

}  // namespace rb

#pragma once
// A scene (docs/formats.md, "Scene (JSON)"): one problem instance as a JSON file,
// read with nlohmann-json and checked completely on load. Every problem with
// the input throws rb::InputError naming the key ("ball.radius",
// "start.velocity", "landscape" with the formula's column, ...); nothing is
// defaulted silently and nothing crashes.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "problems/problem.hpp"

namespace rb {

// The ball of a scene, in scene units (lengths in the landscape's units).
struct SceneBall {
  double radius = 0.0;  // r > 0
  double mass = 0.0;    // m > 0
  // principal moments [I1, I2, I3] about the body axes; absent: homogeneous
  std::optional<Vec3> inertia;
};

// The start of a scene. Exactly one of omega and velocity is set.
struct SceneStart {
  Vec2 contact = Vec2::Zero();   // alpha0 = (x, y) of the contact point
  std::optional<Vec3> omega;     // angular velocity, world frame
  std::optional<Vec3> velocity;  // the centre's velocity u0 (tangential), world frame
  // given as [u_x, u_y]: velocity is then empty until the landscape's slope
  // lifts it onto the tangent plane (start_velocity)
  std::optional<Vec2> horizontal_velocity;
  double spin = 0.0;  // s0 = omega . N, with velocity only
  // The orientation R0 as a unit quaternion (w, x, y, z), normalised on load.
  Eigen::Vector4d orientation = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
};

struct SceneModel;  // scene.cpp: the model a load compiled, and what it was made of

// The range of a scene's t_end (seconds), and of every --t-end: a subnormal
// one (1e-323) makes the steps underflow to 0, an absurd one asks for runs
// no study takes (the longest shipped scene runs 15 s, the full regime grid
// 1000 s, a drift run 10^4 s).
inline constexpr double kMinTEnd = 1e-6, kMaxTEnd = 1e7;

struct Scene {
  std::string name;
  std::string description;               // empty when the file has none
  std::string landscape;                 // the formula text of z = f(x, y)
  std::map<std::string, double> params;  // named constants of the formula
  Domain domain;                         // unbounded when the file has none
  bool has_domain = false;
  SceneBall ball;
  double gravity = 9.81;  // g0 >= 0; gravity is (0, 0, -g0)
  SceneStart start;
  double t_end = 0.0;          // kMinTEnd to kMaxTEnd
  std::string exact = "none";  // a name of exact_names() or "none"
  // first integrals beyond the energy the scene declares (invariant_names()),
  // checked against the landscape and the ball on load
  std::vector<std::string> invariants;
  std::string source = "<text>";  // the file it came from, or "<text>"
  // the JSON text it was parsed from, or a built scene's values as a file
  // would give them (checked_scene): the sweep's cache key
  std::string text;
  // The model parse_scene compiled to check the start: make_problem reuses
  // it while the landscape, params, ball and gravity are those it was made
  // of, so that a load compiles the formula once.
  std::shared_ptr<const SceneModel> checked_model;
};

// Parses and checks a scene. source names where the text came from (kept in
// Scene::source). Throws InputError on any problem, naming the key.
Scene parse_scene(std::string_view json_text, const std::string& source = "<text>");

// Checks a scene built as a value (the regime study's) as parse_scene checks
// a file's (every range, the landscape, the start, the exact solution and
// the invariants; the same InputErrors) and returns it ready for
// make_problem, its orientation normalised.
Scene checked_scene(Scene scene);

// Reads and parses a scene file; an unreadable file throws InputError (key "scene").
Scene load_scene_file(const std::string& path);

// The names of the shipped scenes (the .json files in problems/scenes), sorted.
std::vector<std::string> shipped_scene_names();

// A shipped scene by name ("valley-rest"), or a scene file by path (anything
// ending in ".json" or containing a '/'). An unknown name throws InputError
// (key "scene") listing the shipped ones.
Scene load_scene(const std::string& name_or_path);

// A shipped scene's fields, read and checked as a load does, without its
// model or closed form (nothing compiled): what `rollbench list` prints.
Scene read_shipped_scene(const std::string& name);

// The model of a scene: its landscape with the params, the ball and gravity.
RollingBall make_model(const Scene& scene);

// The centre's start velocity u0: as given, or [u_x, u_y] lifted onto the
// tangent plane, u0 = (u_x, u_y, f_x u_x + f_y u_y). Only for a velocity start.
Vec3 start_velocity(const Scene& scene, const RollingBall& model);

// The start in world frame: omega0 (given, or (N x u0) / r + s0 N), R0 from
// the quaternion, and the flat state y0 = (R0, v0 = T omega0, alpha0).
Vec3 start_omega(const Scene& scene, const RollingBall& model);
Mat3 start_rotation(const Scene& scene);
FlatState start_state(const Scene& scene, const RollingBall& model);

// The problem of a scene, with its exact solution when the scene names one.
Problem make_problem(const Scene& scene);

// Scene files read, scene models built (each compiles a formula) and closed
// forms built in this process so far: a load does each once, and make_problem
// after it none (the tests count them).
struct SceneLoadCounts {
  long files_read = 0;
  long models_built = 0;
  long exacts_built = 0;  // closed forms checked and built (make_exact)
};
SceneLoadCounts scene_load_counts();

}  // namespace rb

#include "problems/scene.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "problems/exact.hpp"
#include "problems/input_error.hpp"
#include "problems/input_file.hpp"
#include "problems/invariants.hpp"
#include "problems/json_limits.hpp"
#include "problems/safe_name.hpp"

namespace rb {

namespace {

using json = nlohmann::json;

std::string join_key(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

std::string list_of(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

// Builds the DOM like nlohmann's own parser, but knows the key it is inside
// of, so that duplicate keys and numbers that overflow a double (1e400) are
// errors naming their key instead of a silent last-wins or a bare message.
class SceneSax final : public nlohmann::json_sax<json> {
 public:
  json root;
  std::optional<InputError> error;

  bool null() override { return put(json(nullptr)) != nullptr; }
  bool boolean(bool b) override { return put(json(b)) != nullptr; }
  bool number_integer(number_integer_t v) override { return put(json(v)) != nullptr; }
  bool number_unsigned(number_unsigned_t v) override { return put(json(v)) != nullptr; }
  bool number_float(number_float_t v, const string_t&) override { return put(json(v)) != nullptr; }
  bool string(string_t& s) override { return put(json(s)) != nullptr; }
  bool binary(binary_t& b) override { return put(json(b)) != nullptr; }
  bool start_object(std::size_t) override {
    frames_.push_back({put(json::object()), {}, {}});
    return true;
  }
  bool key(string_t& k) override {
    Frame& f = frames_.back();
    f.key = k;
    if (!f.seen.insert(k).second) {
      error = InputError("the key appears more than once", path());
      return false;
    }
    return true;
  }
  bool end_object() override {
    frames_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    frames_.push_back({put(json::array()), {}, {}});
    return true;
  }
  bool end_array() override {
    frames_.pop_back();
    return true;
  }
  bool parse_error(std::size_t position, const std::string& last_token, const json::exception& ex) override {
    if (ex.id == 406) {
      error = InputError("the number " + escaped_excerpt(last_token) + " is not a finite double", path());
    } else {
      // without nlohmann's prefix, and its "last read" cut to a short excerpt
      error = InputError("invalid JSON at byte " + std::to_string(position) + ": " + json_error_text(ex.what()));
    }
    return false;
  }

 private:
  struct Frame {
    json* value;
    std::string key;  // the last key read, for objects
    std::set<std::string> seen;
  };
  std::vector<Frame> frames_;

  // the dotted key of the value being read; array elements take their array's key
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_)
      if (f.value->is_object() && !f.key.empty()) p = join_key(p, escaped_excerpt(f.key));
    return p;
  }
  json* put(json v) {
    if (frames_.empty()) {
      root = std::move(v);
      return &root;
    }
    json& parent = *frames_.back().value;
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    return &(parent[frames_.back().key] = std::move(v));
  }
};

json parse_json(std::string_view text) {
  // before parsing: no walk of the document then recurses that deep
  if (const std::size_t at = json_too_deep_at(text); at != std::string_view::npos)
    throw InputError("the scene nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                     std::to_string(at + 1) + ")");
  SceneSax sax;
  const bool ok = json::sax_parse(text, &sax);
  if (sax.error) throw *sax.error;
  if (!ok) throw InputError("invalid JSON");
  return std::move(sax.root);
}

// --- typed access, every error naming its dotted key ---

void reject_unknown_keys(const json& obj, const std::string& where, const std::vector<std::string>& known) {
  for (const auto& item : obj.items())
    if (std::find(known.begin(), known.end(), item.key()) == known.end())
      throw InputError("unknown key (known here: " + list_of(known) + ")",
                       join_key(where, escaped_excerpt(item.key())));
}

const json* optional_key(const json& obj, const char* key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const json& required_key(const json& obj, const std::string& where, const char* key) {
  const json* v = optional_key(obj, key);
  if (!v) throw InputError("missing required key", join_key(where, key));
  return *v;
}

const json& object_at(const json& v, const std::string& key) {
  if (!v.is_object()) throw InputError(std::string("must be an object, not ") + v.type_name(), key);
  return v;
}

double number_at(const json& v, const std::string& key) {
  if (!v.is_number()) throw InputError(std::string("must be a number, not ") + v.type_name(), key);
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError("must be a finite number", key);
  return x;
}

std::string string_at(const json& v, const std::string& key) {
  if (!v.is_string()) throw InputError(std::string("must be a string, not ") + v.type_name(), key);
  return v.get<std::string>();
}

template <int n>
Eigen::Matrix<double, n, 1> vector_at(const json& v, const std::string& key) {
  const std::string want = "must be an array of " + std::to_string(n) + " numbers";
  if (!v.is_array()) throw InputError(want + ", not " + v.type_name(), key);
  if (v.size() != static_cast<std::size_t>(n)) throw InputError(want + ", not " + std::to_string(v.size()), key);
  Eigen::Matrix<double, n, 1> out;
  for (int i = 0; i < n; ++i) {
    if (!v[i].is_number()) throw InputError(want + "; element " + std::to_string(i) + " is a " + v[i].type_name(), key);
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) throw InputError(want + "; element " + std::to_string(i) + " is not finite", key);
  }
  return out;
}

// param names: the formula module's one check, placed under params.<name>
void check_param_name(const std::string& name) {
  try {
    check_formula_param_name(name);
  } catch (const InputError& e) {
    throw e.under(join_key("params", name));
  }
}

// Principal moments a rigid ball can have: positive, the triangle
// inequality, and I1 + I2 + I3 <= 2 m r^2 (the trace of the inertia is
// 2 sum m_i |x_i|^2, and |x_i| <= r); equality up to rounding is allowed.
void check_inertia(const Vec3& I, const SceneBall& ball) {
  const char* key = "ball.inertia";
  const double slack = 1e-12 * I.cwiseAbs().sum();
  for (int k = 0; k < 3; ++k)
    if (!(I[k] > 0.0))
      throw InputError(
          "each principal moment [I1, I2, I3] must be > 0, not I" + std::to_string(k + 1) + " = " + num(I[k]), key);
  for (int k = 0; k < 3; ++k) {
    const double others = I.sum() - I[k];
    if (I[k] > others + slack)
      throw InputError("the moments must obey the triangle inequality, but I" + std::to_string(k + 1) + " = " +
                           num(I[k]) + " > the other two's sum " + num(others),
                       key);
  }
  const double bound = 2.0 * ball.mass * ball.radius * ball.radius;
  if (I.sum() > bound + slack)
    throw InputError("the moments do not fit a ball of this mass and radius: I1 + I2 + I3 = " + num(I.sum()) +
                         " > 2 m r^2 = " + num(bound),
                     key);
}

SceneStart read_start(const json& v) {
  object_at(v, "start");
  reject_unknown_keys(v, "start", {"contact", "omega", "velocity", "spin", "orientation"});
  SceneStart s;
  s.contact = vector_at<2>(required_key(v, "start", "contact"), "start.contact");
  const json* omega = optional_key(v, "omega");
  const json* velocity = optional_key(v, "velocity");
  const json* spin = optional_key(v, "spin");
  if (velocity && !(velocity->is_array() && (velocity->size() == 2 || velocity->size() == 3)))
    throw InputError(std::string("must be an array of 3 numbers (u_x, u_y, u_z) or 2 (u_x, u_y), not ") +
                         (velocity->is_array() ? std::to_string(velocity->size()) + " numbers" : velocity->type_name()),
                     "start.velocity");
  if (omega && velocity) throw InputError("give either omega or velocity (with spin), not both", "start");
  if (!omega && !velocity) throw InputError("missing omega or velocity (with spin): give one of them", "start");
  if (spin && !velocity) throw InputError("spin goes with velocity; with omega the spin is part of it", "start.spin");
  if (omega) s.omega = vector_at<3>(*omega, "start.omega");
  if (velocity && velocity->is_array() && velocity->size() == 2)
    s.horizontal_velocity = vector_at<2>(*velocity, "start.velocity");
  else if (velocity) s.velocity = vector_at<3>(*velocity, "start.velocity");
  if (spin) s.spin = number_at(*spin, "start.spin");
  if (const json* q = optional_key(v, "orientation")) s.orientation = vector_at<4>(*q, "start.orientation");
  return s;
}

// "invariants": an array of names (checked by check_values)
std::vector<std::string> read_invariant_names(const json& v) {
  const char* key = "invariants";
  if (!v.is_array()) throw InputError(std::string("must be an array of names, not ") + v.type_name(), key);
  std::vector<std::string> names;
  for (const json& item : v) names.push_back(string_at(item, key));
  return names;
}

// The scene's keys, their types and shapes; their ranges are check_values'.
Scene read_scene(const json& root, const std::string& source) {
  if (!root.is_object()) throw InputError(std::string("a scene must be a JSON object, not ") + root.type_name());
  reject_unknown_keys(root, "",
                      {"name", "description", "landscape", "params", "domain", "ball", "gravity", "start", "t_end",
                       "exact", "invariants"});
  Scene s;
  s.source = source;
  // a name, never a path: it is shown, and a file name may be made of it
  s.name = string_at(required_key(root, "", "name"), "name");
  if (const json* d = optional_key(root, "description")) s.description = string_at(*d, "description");
  s.landscape = string_at(required_key(root, "", "landscape"), "landscape");
  if (const json* p = optional_key(root, "params")) {
    object_at(*p, "params");
    for (const auto& item : p->items()) s.params[item.key()] = number_at(item.value(), join_key("params", item.key()));
  }
  if (const json* d = optional_key(root, "domain")) {
    const Eigen::Vector4d b = vector_at<4>(*d, "domain");
    s.domain = Domain{b[0], b[1], b[2], b[3]};
    s.has_domain = true;
  }
  const json& ball = object_at(required_key(root, "", "ball"), "ball");
  reject_unknown_keys(ball, "ball", {"radius", "mass", "inertia"});
  s.ball.radius = number_at(required_key(ball, "ball", "radius"), "ball.radius");
  s.ball.mass = number_at(required_key(ball, "ball", "mass"), "ball.mass");
  if (const json* inertia = optional_key(ball, "inertia")) s.ball.inertia = vector_at<3>(*inertia, "ball.inertia");
  if (const json* g = optional_key(root, "gravity")) s.gravity = number_at(*g, "gravity");
  s.start = read_start(required_key(root, "", "start"));
  s.t_end = number_at(required_key(root, "", "t_end"), "t_end");
  if (const json* e = optional_key(root, "exact")) s.exact = string_at(*e, "exact");
  if (const json* inv = optional_key(root, "invariants")) s.invariants = read_invariant_names(*inv);
  return s;
}

void check_finite(double x, const std::string& key) {
  if (!std::isfinite(x)) throw InputError("must be a finite number", key);
}

// The ranges of a scene's values, whether read from a file or built (a
// file's numbers are finite already); normalises the orientation. No
// landscape yet.
void check_values(Scene& s) {
  // a name, never a path: it is shown, and a file name may be made of it
  (void)check_safe_name(s.name, "name");
  for (const auto& [name, value] : s.params) {
    check_param_name(name);
    check_finite(value, join_key("params", name));
  }
  const Domain& d = s.domain;
  if (s.has_domain && (!(d.xmin < d.xmax) || !(d.ymin < d.ymax)))
    throw InputError("[xmin, xmax, ymin, ymax] needs xmin < xmax and ymin < ymax", "domain");
  check_finite(s.ball.radius, "ball.radius");
  check_finite(s.ball.mass, "ball.mass");
  if (!(s.ball.radius > 0.0)) throw InputError("the radius must be > 0", "ball.radius");
  if (!(s.ball.mass > 0.0)) throw InputError("the mass must be > 0", "ball.mass");
  if (s.ball.inertia) check_inertia(*s.ball.inertia, s.ball);
  check_finite(s.gravity, "gravity");
  if (!(s.gravity >= 0.0)) throw InputError("gravity g0 must be >= 0 (it points down, (0, 0, -g0))", "gravity");
  SceneStart& start = s.start;
  const int motions =
      int{start.omega.has_value()} + int{start.velocity.has_value()} + int{start.horizontal_velocity.has_value()};
  if (motions > 1) throw InputError("give either omega or velocity (with spin), not both", "start");
  if (motions == 0) throw InputError("missing omega or velocity (with spin): give one of them", "start");
  check_finite(start.spin, "start.spin");
  const double norm = start.orientation.norm();
  if (!(std::abs(norm - 1.0) <= 1e-6))
    throw InputError("the quaternion [w, x, y, z] must have unit norm, not " + num(norm), "start.orientation");
  start.orientation /= norm;
  check_finite(s.t_end, "t_end");
  // a normal number in stated bounds: a subnormal t_end (1e-323) makes
  // every step underflow to 0, an absurd one asks for runs no study takes
  if (!(s.t_end >= kMinTEnd && s.t_end <= kMaxTEnd))
    throw InputError("t_end must be from 1e-6 to 1e7 (seconds), not " + num(s.t_end), "t_end");
  const std::vector<std::string> known = exact_names();
  if (s.exact != "none" && std::find(known.begin(), known.end(), s.exact) == known.end())
    throw InputError("unknown exact solution '" + escaped_excerpt(s.exact) + "' (known: none, " + list_of(known) + ")",
                     "exact");
  // invariants: known names, each once; whether the landscape has them is
  // checked with the model (make_invariants)
  const std::vector<std::string> invariants = invariant_names();
  for (auto name = s.invariants.begin(); name != s.invariants.end(); ++name) {
    if (std::find(invariants.begin(), invariants.end(), *name) == invariants.end())
      throw InputError("unknown invariant '" + escaped_excerpt(*name) + "' (known: " + list_of(invariants) + ")",
                       "invariants");
    if (std::find(s.invariants.begin(), name, *name) != name)
      throw InputError("the invariant '" + escaped_excerpt(*name) + "' is named more than once", "invariants");
  }
}

// A built scene's values as a scene file would give them: its text, the
// sweep's cache key (a file's is the file's own text).
std::string values_text(const Scene& s) {
  json ball = {{"radius", s.ball.radius}, {"mass", s.ball.mass}};
  if (s.ball.inertia) ball["inertia"] = std::vector<double>(s.ball.inertia->begin(), s.ball.inertia->end());
  const SceneStart& a = s.start;
  json start = {{"contact", {a.contact.x(), a.contact.y()}},
                {"orientation", {a.orientation[0], a.orientation[1], a.orientation[2], a.orientation[3]}}};
  if (a.omega) start["omega"] = std::vector<double>(a.omega->begin(), a.omega->end());
  if (a.velocity) start["velocity"] = std::vector<double>(a.velocity->begin(), a.velocity->end());
  if (a.horizontal_velocity) start["velocity"] = {a.horizontal_velocity->x(), a.horizontal_velocity->y()};
  if (!a.omega) start["spin"] = a.spin;
  json scene = {{"name", s.name},   {"description", s.description}, {"landscape", s.landscape}, {"params", s.params},
                {"ball", ball},     {"gravity", s.gravity},         {"start", start},           {"t_end", s.t_end},
                {"exact", s.exact}, {"invariants", s.invariants}};
  if (s.has_domain) scene["domain"] = {s.domain.xmin, s.domain.xmax, s.domain.ymin, s.domain.ymax};
  return scene.dump(2) + "\n";
}

// What needs the landscape: a regular, finite, tangential start.
void check_start(const Scene& s, const RollingBall& model) {
  const Vec2 a = s.start.contact;
  if (!s.domain.contains(a.x(), a.y())) {
    char where[256];
    std::snprintf(where, sizeof where, "the start contact (%g, %g) lies outside the domain [%g, %g] x [%g, %g]", a.x(),
                  a.y(), s.domain.xmin, s.domain.xmax, s.domain.ymin, s.domain.ymax);
    throw InputError(where, "start.contact");
  }
  const Jet2<double> f = model.landscape().at(a.x(), a.y());
  for (const double d : {f.f, f.fx, f.fy, f.fxx, f.fxy, f.fyy})
    if (!std::isfinite(d))
      throw InputError("the landscape or its derivatives are not finite at the start contact", "start.contact");
  const Vec3 N = model.normal_at(a.x(), a.y());
  if (s.start.velocity) {
    const Vec3& u = *s.start.velocity;
    if (std::abs(u.dot(N)) > 1e-9 * u.norm())
      throw InputError("the centre's velocity has a normal component u0 . N = " + num(u.dot(N)) +
                           "; only its tangential part can be realised (or give [u_x, u_y] and the slope fixes u_z)",
                       "start.velocity");
  }
  const FlatState y0 = start_state(s, model);
  if (!y0.allFinite()) throw InputError("the start state is not finite (ball or start values too large)", "start");
  // T and T^-1 must survive double range (r = 1e-200 makes m r^2 vanish)
  const Vec3 omega0 = start_omega(s, model);
  const Vec3 omega_back = model.omega_from_momentum(rotation_of(y0), N, Vec3(momentum_of(y0)));
  if (!omega_back.allFinite() || (omega_back - omega0).norm() > 1e-9 * (1.0 + omega0.norm()))
    throw InputError("the ball's radius and mass are too extreme for its inertia to be represented in doubles", "ball");
  const ModelMargins m = model.margins_at(y0);
  if (!m.regular())
    throw InputError("the contact is not regular: r * max curvature = " + num(m.r_kappa_max()) +
                         " (must be < 1: the ball does not fit the landscape there)",
                     "start.contact");
  if (!(m.normal_force > 0.0))
    throw InputError("the ball leaves the surface at once: the normal force F . N = " + num(m.normal_force) +
                         " at the start is not > 0 (too fast over a crest, or no gravity)",
                     "start");
}

// what scene_load_counts reports (loads may run on several threads)
std::atomic<long> files_read{0}, models_built{0}, exacts_built{0};

// the closed form a scene names (nullptr for "none"), counted
std::shared_ptr<const ExactSolution> build_exact(const Scene& scene, const RollingBall& model) {
  ++exacts_built;
  return make_exact(scene, model);
}

}  // namespace

struct SceneModel {
  // what it was made of
  std::string landscape;
  std::map<std::string, double> params;
  SceneBall ball;
  double gravity;
  RollingBall model;
  // the closed form the load checked, and what it depends on besides the model
  std::string exact_name;
  SceneStart start;
  std::shared_ptr<const ExactSolution> exact;

  bool made_of(const Scene& s) const {
    return s.landscape == landscape && s.params == params && s.ball.radius == ball.radius && s.ball.mass == ball.mass &&
           s.ball.inertia == ball.inertia && s.gravity == gravity;
  }
  // the scene may be changed after the load (a sweep's t_end): the exact
  // solution is reused only when nothing it was made from changed
  bool exact_fits(const Scene& s) const {
    const SceneStart& a = s.start;
    return made_of(s) && s.exact == exact_name && a.contact == start.contact && a.omega == start.omega &&
           a.velocity == start.velocity && a.horizontal_velocity == start.horizontal_velocity && a.spin == start.spin &&
           a.orientation == start.orientation;
  }
};

SceneLoadCounts scene_load_counts() { return {files_read.load(), models_built.load(), exacts_built.load()}; }

RollingBall make_model(const Scene& scene) {
  ++models_built;
  try {
    return RollingBall(Landscape::parse(scene.landscape, scene.params),
                       BallParams{scene.ball.radius, scene.ball.mass, scene.gravity, scene.ball.inertia});
  } catch (const InputError& e) {
    throw e.under("landscape");
  }
}

Vec3 start_velocity(const Scene& scene, const RollingBall& model) {
  if (scene.start.velocity) return *scene.start.velocity;
  const Vec2 a = scene.start.contact;
  const Vec2 u = scene.start.horizontal_velocity.value();
  const Jet2<double> f = model.landscape().at(a.x(), a.y());
  return Vec3(u.x(), u.y(), f.fx * u.x() + f.fy * u.y());
}

Vec3 start_omega(const Scene& scene, const RollingBall& model) {
  if (scene.start.omega) return *scene.start.omega;
  const Vec2 a = scene.start.contact;
  const Vec3 N = model.normal_at(a.x(), a.y());
  return N.cross(start_velocity(scene, model)) / scene.ball.radius + scene.start.spin * N;
}

Mat3 start_rotation(const Scene& scene) {
  const Eigen::Vector4d& q = scene.start.orientation;
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

FlatState start_state(const Scene& scene, const RollingBall& model) {
  const Vec2 a = scene.start.contact;
  const Vec3 N = model.normal_at(a.x(), a.y());
  const Mat3 R0 = start_rotation(scene);
  return make_flat(R0, model.momentum_from_omega(R0, N, start_omega(scene, model)), a);
}

Scene parse_scene(std::string_view json_text, const std::string& source) {
  Scene scene = read_scene(parse_json(json_text), source);
  scene.text = std::string(json_text);
  return checked_scene(std::move(scene));
}

Scene checked_scene(Scene scene) {
  check_values(scene);
  RollingBall model = make_model(scene);
  check_start(scene, model);
  auto exact = build_exact(scene, model);  // throws (key "exact") when it does not fit the scene
  (void)make_invariants(scene, model);     // throws (key "invariants") when the landscape lacks one
  if (scene.text.empty()) scene.text = values_text(scene);
  scene.checked_model = std::make_shared<const SceneModel>(SceneModel{
      scene.landscape, scene.params, scene.ball, scene.gravity, std::move(model), scene.exact, scene.start, exact});
  return scene;
}

namespace {

// a regular file of at most 1 MiB (problems/input_file.hpp), whoever names it:
// the command line, a sweep's --scenes, a peer file's "scene"
std::string read_scene_text(const std::string& path) {
  std::string text = read_input_file(path, kSceneInput, "scene");
  ++files_read;
  return text;
}

}  // namespace

Scene load_scene_file(const std::string& path) { return parse_scene(read_scene_text(path), path); }

std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(RB_SCENE_DIR, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Scene load_scene(const std::string& name_or_path) {
  const bool is_path =
      name_or_path.find('/') != std::string::npos || (name_or_path.size() > 5 && name_or_path.ends_with(".json"));
  if (is_path) return load_scene_file(name_or_path);
  const std::vector<std::string> names = shipped_scene_names();
  if (std::find(names.begin(), names.end(), name_or_path) == names.end())
    throw InputError("unknown scene '" + escaped_excerpt(name_or_path) + "' (shipped: " + list_of(names) +
                         "; a scene file is given by a path ending in .json)",
                     "scene");
  return load_scene_file(std::string(RB_SCENE_DIR) + "/" + name_or_path + ".json");
}

Scene read_shipped_scene(const std::string& name) {
  const std::string path = std::string(RB_SCENE_DIR) + "/" + name + ".json";
  return read_scene(parse_json(read_scene_text(path)), path);
}

Problem make_problem(const Scene& scene) {
  const SceneModel* checked = scene.checked_model.get();
  RollingBall model = checked != nullptr && checked->made_of(scene) ? checked->model : make_model(scene);
  const FlatState y0 = start_state(scene, model);
  auto exact = checked != nullptr && checked->exact_fits(scene) ? checked->exact : build_exact(scene, model);
  auto invariants = make_invariants(scene, model);
  return Problem(scene.name, std::move(model), y0, scene.t_end, scene.domain, std::move(exact), std::move(invariants));
}

}  // namespace rb

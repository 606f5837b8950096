// The scene format (docs/formats.md, "Scene (JSON)"): every shipped scene loads
// and is valid at its start; every kind of bad input is an InputError that
// names its key (and the formula's column); the start conversion of docs/model.md.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "problems/exact.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace rb {
namespace {

using json = nlohmann::json;

// A small valid scene; each error test breaks one thing in it.
json base_scene() {
  return json::parse(R"({
    "name": "test", "description": "a valid scene",
    "landscape": "a*x^2 - y/10", "params": { "a": 0.1 },
    "domain": [-2, 2, -2, 2],
    "ball": { "radius": 0.1, "mass": 1.0 }, "gravity": 9.81,
    "start": { "contact": [0.0, 0.0], "velocity": [0.5, 0.0, 0.0], "spin": 0.0,
               "orientation": [1, 0, 0, 0] },
    "t_end": 1.0, "exact": "none" })");
}

// Parses text and returns the InputError it must throw.
InputError error_of(const std::string& text) {
  try {
    parse_scene(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for: " << text;
  return InputError("none", "<no error>");
}

void expect_key(const json& scene, const std::string& key, int column = 0) {
  const InputError e = error_of(scene.dump());
  EXPECT_EQ(e.key(), key) << e.what() << "\n  scene: " << scene.dump();
  EXPECT_EQ(e.column(), column) << e.what();
}

TEST(SceneShipped, EveryShippedSceneLoadsAndStartsValid) {
  const std::vector<std::string> expected = {"bowl-3d",
                                             "bowl-planar",
                                             "bumpy-long",
                                             "chaplygin-bowl",
                                             "chaplygin-bumpy-long",
                                             "chaplygin-plane",
                                             "chaplygin-valley",
                                             "gaussian-hills",
                                             "gaussian-hills-chaplygin",
                                             "incline-spin",
                                             "paraboloid",
                                             "paraboloid-chaplygin",
                                             "paraboloid-perturbed",
                                             "paraboloid-perturbed-chaplygin",
                                             "plane",
                                             "saddle",
                                             "valley-rest",
                                             "valley-sideways"};
  const std::vector<std::string> names = shipped_scene_names();
  EXPECT_EQ(names, expected);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Scene scene = load_scene(name);
    EXPECT_EQ(scene.name, name);  // the file's stem is its name
    EXPECT_FALSE(scene.description.empty()) << "a shipped scene says what it tests";
    EXPECT_EQ(scene.source, std::string(RB_SCENE_DIR) + "/" + name + ".json");
    const Problem problem = make_problem(scene);
    EXPECT_EQ(problem.name(), name);
    EXPECT_EQ(problem.t_end(), scene.t_end);
    const Validity v = problem.check_full(problem.y0());
    EXPECT_EQ(v.status, Status::ok) << v.reason;
    EXPECT_EQ(problem.exact() != nullptr, scene.exact != "none");
  }
}

TEST(SceneShipped, LoadsByPathAndByName) {
  const Scene by_name = load_scene("plane");
  const Scene by_path = load_scene(std::string(RB_SCENE_DIR) + "/plane.json");
  EXPECT_EQ(by_name.landscape, by_path.landscape);
  EXPECT_EQ(by_name.exact, "plane");
  EXPECT_EQ(load_scene(std::string(RB_TEST_DATA) + "/stop-domain.json").name, "stop-domain");
}

TEST(SceneParse, ReadsEveryFieldAndTheDefaults) {
  const Scene s = parse_scene(base_scene().dump());
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.landscape, "a*x^2 - y/10");
  EXPECT_EQ(s.params.at("a"), 0.1);
  EXPECT_TRUE(s.has_domain);
  EXPECT_EQ(s.domain.xmin, -2.0);
  EXPECT_EQ(s.domain.ymax, 2.0);
  EXPECT_EQ(s.ball.radius, 0.1);
  EXPECT_EQ(s.ball.mass, 1.0);
  EXPECT_EQ(s.source, "<text>");

  json minimal = base_scene();
  for (const char* key : {"description", "params", "domain", "gravity", "exact"}) minimal.erase(key);
  minimal["landscape"] = "x^2/10";
  minimal["start"].erase("orientation");
  minimal["start"].erase("spin");
  const Scene m = parse_scene(minimal.dump(), "mine.json");
  EXPECT_EQ(m.source, "mine.json");
  EXPECT_EQ(m.gravity, 9.81);
  EXPECT_EQ(m.exact, "none");
  EXPECT_EQ(m.start.spin, 0.0);
  EXPECT_EQ(m.start.orientation, Eigen::Vector4d(1, 0, 0, 0));
  EXPECT_FALSE(m.has_domain);
  EXPECT_TRUE(m.domain.contains(1e300, -1e300));
  EXPECT_TRUE(m.description.empty());
  EXPECT_EQ(make_problem(m).exact(), nullptr);
}

TEST(SceneErrors, InvalidJsonSaysTheBytePosition) {
  const InputError e = error_of(R"({"name": "a", "landscape": })");
  EXPECT_EQ(e.key(), "");
  EXPECT_NE(e.message().find("invalid JSON at byte 28"), std::string::npos) << e.what();
  EXPECT_EQ(error_of("").key(), "");
  EXPECT_EQ(error_of("[1, 2]").key(), "");  // not an object
  EXPECT_NE(error_of(base_scene().dump() + " {}").message().find("invalid JSON"), std::string::npos);
}

TEST(SceneErrors, DuplicateKeysAndHugeNumbersNameTheirKey) {
  EXPECT_EQ(error_of(R"({"name": "a", "name": "b"})").key(), "name");
  EXPECT_EQ(error_of(R"({"ball": {"radius": 1, "radius": 2}})").key(), "ball.radius");
  std::string text = base_scene().dump();
  text.replace(text.find("\"radius\":0.1"), 12, "\"radius\":1e400");
  EXPECT_EQ(error_of(text).key(), "ball.radius");
  text = base_scene().dump();
  text.replace(text.find("\"t_end\":1.0"), 11, "\"t_end\":-1e999");
  EXPECT_EQ(error_of(text).key(), "t_end");
  text = base_scene().dump();
  text.replace(text.find("\"contact\":[0.0,0.0]"), 19, "\"contact\":[0.0,2e308]");
  EXPECT_EQ(error_of(text).key(), "start.contact");
}

TEST(SceneErrors, MissingRequiredKeys) {
  for (const char* key : {"name", "landscape", "ball", "start", "t_end"}) {
    json s = base_scene();
    s.erase(key);
    expect_key(s, key);
  }
  for (const char* key : {"radius", "mass"}) {
    json s = base_scene();
    s["ball"].erase(key);
    expect_key(s, std::string("ball.") + key);
  }
  json s = base_scene();
  s["start"].erase("contact");
  expect_key(s, "start.contact");
}

TEST(SceneErrors, UnknownKeysAtEveryLevel) {
  json s = base_scene();
  s["colour"] = "red";
  expect_key(s, "colour");
  s = base_scene();
  s["ball"]["colour"] = "red";
  expect_key(s, "ball.colour");
  s = base_scene();
  s["start"]["velocty"] = {0, 0, 0};
  expect_key(s, "start.velocty");
}

TEST(SceneErrors, WrongTypes) {
  const std::vector<std::pair<json::json_pointer, json>> cases = {
      {json::json_pointer("/name"), 3},
      {json::json_pointer("/description"), false},
      {json::json_pointer("/landscape"), json::array()},
      {json::json_pointer("/params"), json::array({1})},
      {json::json_pointer("/params/a"), "0.1"},
      {json::json_pointer("/domain"), json::object()},
      {json::json_pointer("/ball"), 0.1},
      {json::json_pointer("/ball/radius"), "0.1"},
      {json::json_pointer("/ball/mass"), nullptr},
      {json::json_pointer("/gravity"), true},
      {json::json_pointer("/start"), json::array()},
      {json::json_pointer("/start/contact"), 0.0},
      {json::json_pointer("/start/spin"), "fast"},
      {json::json_pointer("/t_end"), "1"},
      {json::json_pointer("/exact"), 1},
  };
  for (const auto& [pointer, value] : cases) {
    json s = base_scene();
    s[pointer] = value;
    std::string key = pointer.to_string().substr(1);
    std::replace(key.begin(), key.end(), '/', '.');
    expect_key(s, key);
  }
  json s = base_scene();
  s["start"]["contact"] = {0.0, "1"};
  expect_key(s, "start.contact");
}

TEST(SceneErrors, WrongArrayLengths) {
  json s = base_scene();
  s["start"]["contact"] = {0.0};
  expect_key(s, "start.contact");
  s = base_scene();
  s["start"]["velocity"] = {0.5};  // 2 numbers are the horizontal part, 3 the whole
  expect_key(s, "start.velocity");
  s["start"]["velocity"] = {0.5, 0.0, 0.0, 0.0};
  expect_key(s, "start.velocity");
  s = base_scene();
  s["domain"] = {-1, 1, -1};
  expect_key(s, "domain");
  s = base_scene();
  s["start"]["orientation"] = {1, 0, 0};
  expect_key(s, "start.orientation");
  s = base_scene();
  s["start"].erase("velocity");
  s["start"].erase("spin");
  s["start"]["omega"] = {1, 2, 3, 4};
  expect_key(s, "start.omega");
}

TEST(SceneErrors, OutOfRangeValues) {
  const std::vector<std::pair<json::json_pointer, json>> cases = {
      {json::json_pointer("/ball/radius"), 0.0}, {json::json_pointer("/ball/radius"), -0.1},
      {json::json_pointer("/ball/mass"), 0.0},   {json::json_pointer("/gravity"), -9.81},
      {json::json_pointer("/t_end"), 0.0},       {json::json_pointer("/t_end"), -1.0},
  };
  for (const auto& [pointer, value] : cases) {
    json s = base_scene();
    s[pointer] = value;
    std::string key = pointer.to_string().substr(1);
    std::replace(key.begin(), key.end(), '/', '.');
    expect_key(s, key);
  }
  for (const json& d : {json{-1, -1, -2, 2}, json{-1, 1, 2, -2}}) {
    json s = base_scene();
    s["domain"] = d;
    expect_key(s, "domain");
  }
  // a radius whose r^2 underflows leaves no inertia to integrate
  json s = base_scene();
  s["ball"]["radius"] = 1e-200;
  s["params"]["a"] = 0.0;
  expect_key(s, "ball");
  s = base_scene();
  s["gravity"] = 0.0;  // a weightless scene is allowed
  EXPECT_NO_THROW(parse_scene(s.dump()));
}

// A scene built as a value (the regime study's) passes the checks a file
// does, with the same errors: each file case above, broken in the value
// parsed from the valid scene, is refused by checked_scene naming its key.
TEST(SceneErrors, BuiltScenesGetTheFileChecks) {
  const Scene valid = parse_scene(base_scene().dump());
  auto message_of = [](Scene s) {
    s.text.clear();
    try {
      (void)checked_scene(std::move(s));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto file_message_of = [](const json& broken) { return std::string(error_of(broken.dump()).what()); };
  Scene s = valid;
  s.ball.radius = -0.1;
  json f = base_scene();
  f["ball"]["radius"] = -0.1;
  EXPECT_EQ(message_of(s), file_message_of(f));
  s = valid;
  s.gravity = -9.81;
  f = base_scene();
  f["gravity"] = -9.81;
  EXPECT_EQ(message_of(s), file_message_of(f));
  s = valid;
  s.domain.xmax = -3.0;
  f = base_scene();
  f["domain"] = {-2, -3, -2, 2};
  EXPECT_EQ(message_of(s), file_message_of(f));
  s = valid;
  s.name = "../up";
  f = base_scene();
  f["name"] = "../up";
  EXPECT_EQ(message_of(s), file_message_of(f));
  s = valid;
  s.start.orientation = Eigen::Vector4d(2.0, 0.0, 0.0, 0.0);
  f = base_scene();
  f["start"]["orientation"] = {2, 0, 0, 0};
  EXPECT_EQ(message_of(s), file_message_of(f));
  s = valid;
  s.start.contact = Vec2(5.0, 0.0);
  f = base_scene();
  f["start"]["contact"] = {5.0, 0.0};
  EXPECT_EQ(message_of(s), file_message_of(f));
  s = valid;
  s.invariants = {"nope"};
  f = base_scene();
  f["invariants"] = json::array({"nope"});
  EXPECT_EQ(message_of(s), file_message_of(f));
  // only value checks a file's reader makes impossible: a built scene's own
  s = valid;
  s.start.omega = Vec3(0.0, 0.0, 1.0);
  EXPECT_EQ(message_of(s), "'start': give either omega or velocity (with spin), not both");
  s = valid;
  s.t_end = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message_of(s), "'t_end': must be a finite number");
  // a valid one is checked as the file was, and its text (the sweep's
  // cache key) lists its values: parsed, it is the same scene
  const Scene built = checked_scene([&] {
    Scene b = valid;
    b.text.clear();
    return b;
  }());
  const Scene again = parse_scene(built.text);
  EXPECT_EQ(again.name, valid.name);
  EXPECT_EQ(again.params, valid.params);
  EXPECT_EQ(again.start.velocity, valid.start.velocity);
  EXPECT_EQ(again.start.orientation, valid.start.orientation);
  EXPECT_EQ(again.t_end, valid.t_end);
  EXPECT_EQ(make_problem(again).y0(), make_problem(valid).y0());
}

TEST(SceneErrors, StartNeedsOmegaXorVelocity) {
  json s = base_scene();
  s["start"]["omega"] = {0, 0, 0};
  expect_key(s, "start");  // both
  s["start"].erase("velocity");
  s["start"].erase("spin");
  EXPECT_NO_THROW(parse_scene(s.dump()));
  s["start"].erase("omega");
  expect_key(s, "start");  // neither
  s = base_scene();
  s["start"].erase("velocity");
  s["start"]["omega"] = {0, 0, 0};
  expect_key(s, "start.spin");  // spin without velocity
}

TEST(SceneErrors, VelocityWithANormalComponent) {
  // at (0, 0) the landscape a x^2 - y/10 has N ~ (0, 0.1, 1)
  json s = base_scene();
  s["start"]["velocity"] = {0.0, 1.0, 0.0};
  expect_key(s, "start.velocity");
  s["start"]["velocity"] = {0.0, 1.0, -0.1};  // tangential
  EXPECT_NO_THROW(parse_scene(s.dump()));
}

TEST(SceneErrors, QuaternionMustBeUnit) {
  json s = base_scene();
  s["start"]["orientation"] = {1.0, 0.1, 0.0, 0.0};
  expect_key(s, "start.orientation");
  s["start"]["orientation"] = {0.0, 0.0, 0.0, 0.0};
  expect_key(s, "start.orientation");
  // within 1e-6 it is accepted and normalised
  s["start"]["orientation"] = {1.0 + 5e-7, 0.0, 0.0, 0.0};
  const Scene scene = parse_scene(s.dump());
  EXPECT_NEAR(scene.start.orientation.norm(), 1.0, 1e-15);
}

TEST(SceneErrors, StartOutsideDomainIrregularOrNotFinite) {
  json s = base_scene();
  s["start"]["contact"] = {3.0, 0.0};
  expect_key(s, "start.contact");
  // the message says the point and the domain it missed
  EXPECT_STREQ(error_of(s.dump()).what(),
               "'start.contact': the start contact (3, 0) lies outside the domain [-2, 2] x [-2, 2]");
  // r * kappa = 0.1 * 20 >= 1: the ball does not fit the valley
  s = base_scene();
  s["params"]["a"] = 10.0;
  expect_key(s, "start.contact");
  // sqrt(x) is not finite left of 0, and its slope is infinite at 0
  s = base_scene();
  s["landscape"] = "sqrt(x + a)";
  s["start"]["contact"] = {-0.5, 0.0};
  s["start"]["velocity"] = {0.0, 0.0, 0.0};
  expect_key(s, "start.contact");
  s["start"]["contact"] = {-0.1, 0.0};
  expect_key(s, "start.contact");
}

TEST(SceneErrors, LandscapeFormulaErrorsCarryTheirColumn) {
  json s = base_scene();
  s["landscape"] = "x + * y";
  expect_key(s, "landscape", 5);
  s["landscape"] = "a*x^2 + b";  // b is not a param
  expect_key(s, "landscape", 9);
  s["landscape"] = "sin(x)+abs(y)";  // not smooth
  expect_key(s, "landscape", 8);
  s["landscape"] = "";
  EXPECT_EQ(error_of(s.dump()).key(), "landscape");
}

TEST(SceneErrors, BadParamNames) {
  for (const char* name : {"x", "pi", "sin", "2a", "a-b", ""}) {
    json s = base_scene();
    s["params"][name] = 1.0;
    expect_key(s, std::string("params.") + name);
  }
}

TEST(SceneErrors, UnknownExactNameListsTheKnownOnes) {
  json s = base_scene();
  s["exact"] = "pendulum";
  const InputError e = error_of(s.dump());
  EXPECT_EQ(e.key(), "exact");
  for (const std::string& name : exact_names()) EXPECT_NE(e.message().find(name), std::string::npos) << e.what();
}

TEST(SceneErrors, InertiaIsChecked) {
  json s = base_scene();
  s["ball"]["inertia"] = {0.003, 0.004, 0.005};
  EXPECT_NO_THROW(parse_scene(s.dump()));
  s["ball"]["inertia"] = {0.002, 0.004, 0.006};  // triangle and fit at equality: allowed
  EXPECT_NO_THROW(parse_scene(s.dump()));
  s["ball"]["inertia"] = {0.02 / 3, 0.02 / 3, 0.02 / 3};  // a thin shell: sum = 2 m r^2
  EXPECT_NO_THROW(parse_scene(s.dump()));
  for (const json& bad : {json{0.003, 0.004}, json(0.004), json{0.0, 0.004, 0.004}, json{0.004, -1e-3, 0.004},
                          json{0.001, 0.002, 0.0031}, json{0.0067, 0.0067, 0.0067}}) {
    s["ball"]["inertia"] = bad;
    expect_key(s, "ball.inertia");
  }
  // a closed form of the homogeneous ball does not hold for another
  s["ball"]["inertia"] = {0.003, 0.004, 0.005};
  s["exact"] = "bowl-pendulum";
  expect_key(s, "exact");
}

TEST(SceneErrors, ExactSolutionMustMatchTheScene) {
  json s = base_scene();
  s["exact"] = "plane";  // the landscape is not flat
  expect_key(s, "exact");
  s = base_scene();
  s["landscape"] = "-s*y";
  s["params"] = {{"s", 0.1}};
  s["start"]["velocity"] = {0.5, 0.0, 0.0};
  s["exact"] = "incline";
  EXPECT_NO_THROW(parse_scene(s.dump()));
  s["landscape"] = "-0.2*y";  // s does not match
  expect_key(s, "exact");
  s["params"] = json::object();  // no s
  expect_key(s, "exact");
  s = base_scene();
  s["landscape"] = "rho - sqrt(rho^2 - x^2 - y^2)";
  s["params"] = {{"rho", 1.0}};
  s["start"]["contact"] = {0.5, 0.0};
  s["exact"] = "bowl-pendulum";
  s["start"]["velocity"] = {0.0, 0.0, 0.0};
  EXPECT_NO_THROW(parse_scene(s.dump()));
  s["start"]["velocity"] = {0.0, 0.1, 0.0};  // not at rest
  expect_key(s, "exact");
  s["start"]["velocity"] = {0.0, 0.0, 0.0};
  s["landscape"] = "rho - sqrt(rho^2 - x^2 - 2*y^2)";  // not spherical
  expect_key(s, "exact");
}

TEST(SceneErrors, UnknownSceneNamesAndUnreadableFiles) {
  try {
    load_scene("no-such-scene");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "scene");
    EXPECT_NE(e.message().find("valley-rest"), std::string::npos) << "lists the shipped scenes: " << e.what();
  }
  EXPECT_THROW(load_scene("/no/such/file.json"), InputError);
  EXPECT_THROW(load_scene_file(RB_SCENE_DIR), InputError);  // a directory
}

TEST(SceneStart, VelocityAndSpinBecomeOmega) {
  // a sloped start: N ~ (0, 0.1, 1), u0 tangential, spin 0.7
  json s = base_scene();
  s["start"]["velocity"] = {0.3, 0.5, -0.05};
  s["start"]["spin"] = 0.7;
  const Scene scene = parse_scene(s.dump());
  const Problem problem = make_problem(scene);
  const RollingBall& model = problem.model();
  const Vec3 N = model.normal_at(0.0, 0.0);
  const Vec3 omega0 = start_omega(scene, model);
  EXPECT_NEAR(omega0.dot(N), 0.7, 1e-14);
  EXPECT_LT((0.1 * omega0.cross(N) - Vec3(0.3, 0.5, -0.05)).norm(), 1e-14);
  // the flat state carries v0 = T omega0, and the model gives omega0 back
  const FlatState& y0 = problem.y0();
  EXPECT_LT((model.omega_from_momentum(rotation_of(y0), N, Vec3(momentum_of(y0))) - omega0).norm(), 1e-14);
  EXPECT_LT((model.derived(y0).centre_velocity - Vec3(0.3, 0.5, -0.05)).norm(), 1e-14);
  EXPECT_NEAR(model.derived(y0).spin, 0.7, 1e-14);
  EXPECT_EQ(contact_of(y0), Vec2(0.0, 0.0));
}

TEST(SceneStart, OmegaIsTakenAsGivenAndTheQuaternionBecomesR0) {
  json s = base_scene();
  s["start"].erase("velocity");
  s["start"].erase("spin");
  s["start"]["omega"] = {1.0, -2.0, 3.0};
  // a rotation by 1 rad about (1, 2, 2) / 3
  const double c = std::cos(0.5), sn = std::sin(0.5);
  s["start"]["orientation"] = {c, sn / 3, 2 * sn / 3, 2 * sn / 3};
  const Scene scene = parse_scene(s.dump());
  const Problem problem = make_problem(scene);
  const Vec3 N = problem.model().normal_at(0.0, 0.0);
  EXPECT_LT((problem.model().omega_from_momentum(rotation_of(problem.y0()), N, Vec3(momentum_of(problem.y0()))) -
             Vec3(1, -2, 3))
                .norm(),
            1e-13);
  const Mat3 R0 = rotation_of(problem.y0());
  EXPECT_LT((R0 - so3_exp(Vec3(1, 2, 2) / 3.0)).norm(), 1e-15);
}

}  // namespace
}  // namespace rb

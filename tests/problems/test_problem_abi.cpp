// librollbench_problem.so (problems/abi/rollbench_problem.h), loaded with
// dlopen as a program outside the suite loads it: its right-hand side and
// Jacobian are the suite's bit for bit, its codes are the model's checks, and
// bad input is an error with the loader's message, never a crash.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "problems/abi/rollbench_problem.h"
#include "problems/jacobian.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace rb {
namespace {

// Bit for bit, but a NaN equals any NaN: the sign of a NaN made by an
// invalid operation depends on the order GCC gives a commutative
// operation's operands, which differs where the right-hand side is inlined
// into different code (the library's and this test's).
bool same_bits(const double* a, const double* b, int n) {
  for (int i = 0; i < n; ++i)
    if (std::isnan(a[i]) ? !std::isnan(b[i]) : std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return false;
  return true;
}

// The library's functions, looked up by name as ctypes does.
struct ProblemLibrary {
  void* handle = nullptr;
  decltype(&rb_problem_abi_version) abi_version = nullptr;
  decltype(&rb_problem_open) open = nullptr;
  decltype(&rb_problem_close) close = nullptr;
  decltype(&rb_problem_name) name = nullptr;
  decltype(&rb_problem_state_size) state_size = nullptr;
  decltype(&rb_problem_component_name) component_name = nullptr;
  decltype(&rb_problem_initial_state) initial_state = nullptr;
  decltype(&rb_problem_t_end) t_end = nullptr;
  decltype(&rb_problem_rhs) rhs = nullptr;
  decltype(&rb_problem_jacobian) jacobian = nullptr;
  decltype(&rb_problem_check) check = nullptr;
  decltype(&rb_problem_message) message = nullptr;
  decltype(&rb_problem_rhs_evals) rhs_evals = nullptr;
  decltype(&rb_problem_jacobian_evals) jacobian_evals = nullptr;
  decltype(&rb_problem_reset_counters) reset_counters = nullptr;

  ProblemLibrary() {
    handle = dlopen(RB_PROBLEM_LIB, RTLD_NOW | RTLD_LOCAL);
    if (!handle) return;
    bind(abi_version, "rb_problem_abi_version");
    bind(open, "rb_problem_open");
    bind(close, "rb_problem_close");
    bind(name, "rb_problem_name");
    bind(state_size, "rb_problem_state_size");
    bind(component_name, "rb_problem_component_name");
    bind(initial_state, "rb_problem_initial_state");
    bind(t_end, "rb_problem_t_end");
    bind(rhs, "rb_problem_rhs");
    bind(jacobian, "rb_problem_jacobian");
    bind(check, "rb_problem_check");
    bind(message, "rb_problem_message");
    bind(rhs_evals, "rb_problem_rhs_evals");
    bind(jacobian_evals, "rb_problem_jacobian_evals");
    bind(reset_counters, "rb_problem_reset_counters");
  }
  ~ProblemLibrary() {
    if (handle) dlclose(handle);
  }
  template <class F>
  void bind(F& f, const char* symbol) {
    f = reinterpret_cast<F>(dlsym(handle, symbol));
  }
  bool complete() const {
    return handle && abi_version && open && close && name && state_size && component_name && initial_state && t_end &&
           rhs && jacobian && check && message && rhs_evals && jacobian_evals && reset_counters;
  }
};

const ProblemLibrary& library() {
  static const ProblemLibrary lib;
  return lib;
}

class ProblemAbi : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(library().complete()) << RB_PROBLEM_LIB << ": " << dlerror(); }
  const ProblemLibrary& lib = library();
};

// A state around the start with a random orientation, perturbed off SO(3)
// as a flat method drifts, and momentum and contact spread wide enough that
// some states are beyond the model's limits.
FlatState random_state(const Problem& problem, std::mt19937& rng, const Vec2& centre) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat3 R = so3_exp(Vec3(u(rng), u(rng), u(rng)) * 2.0);
  for (int k = 0; k < 9; ++k) R(k / 3, k % 3) += 1e-3 * u(rng);
  const double scale = problem.model().params().mass * std::pow(problem.model().params().radius, 2);
  const Vec3 v = momentum_of(problem.y0()) + scale * Vec3(u(rng), u(rng), u(rng)) * 40.0;
  return make_flat(R, v, centre + Vec2(u(rng), u(rng)) * 0.5);
}

TEST_F(ProblemAbi, RhsJacobianAndCodesAreTheSuitesBitForBit) {
  EXPECT_EQ(lib.abi_version(), ROLLBENCH_PROBLEM_ABI_VERSION);
  std::mt19937 rng(27);
  // homogeneous and anisotropic balls, smooth and curved landscapes, and a
  // fast ball around a narrow crest, where most states are beyond lift-off
  const std::string crest = RB_TEST_DATA "/stop-lift-off.json";
  for (const std::string& scene : {std::string("valley-sideways"), std::string("chaplygin-valley"),
                                   std::string("gaussian-hills"), std::string("bowl-3d"), crest}) {
    SCOPED_TRACE(scene);
    char error[256] = "unset";
    rb_problem* p = lib.open(scene.c_str(), 0.0, error, sizeof error);
    ASSERT_NE(p, nullptr) << error;
    EXPECT_STREQ(error, "");
    const Problem problem = make_problem(load_scene(scene));
    EXPECT_EQ(lib.name(p), problem.name());
    EXPECT_EQ(lib.t_end(p), problem.t_end());
    ASSERT_EQ(lib.state_size(p), kFlatSize);
    FlatState y0;
    ASSERT_EQ(lib.initial_state(p, y0.data()), ROLLBENCH_PROBLEM_OK);
    EXPECT_EQ(y0, problem.y0());
    int beyond = 0;
    for (int i = 0; i < 200; ++i) {
      const FlatState y = random_state(problem, rng, scene == crest ? Vec2::Zero() : contact_of(problem.y0()));
      FlatState dy_abi, dy_suite;
      ModelMargins margins;
      const int code = lib.rhs(p, 0.5, y.data(), dy_abi.data());
      problem.flat_rhs(y.data(), dy_suite.data(), margins);
      ASSERT_TRUE(same_bits(dy_abi.data(), dy_suite.data(), kFlatSize)) << "state " << i;
      const Validity v = problem.check_model(margins);
      ASSERT_EQ(code, static_cast<int>(v.status)) << "state " << i;
      EXPECT_EQ(lib.message(p), v.reason);
      beyond += code != ROLLBENCH_PROBLEM_OK;
      FlatJacobian J_abi, J_suite;
      lib.jacobian(p, 0.0, y.data(), J_abi.data());
      flat_jacobian(problem, y, J_suite);
      ASSERT_EQ(std::memcmp(J_abi.data(), J_suite.data(), sizeof J_abi), 0) << "state " << i;
      ASSERT_EQ(lib.check(p, y.data()), static_cast<int>(problem.check_full(y).status));
    }
    EXPECT_EQ(lib.rhs_evals(p), 200);
    EXPECT_EQ(lib.jacobian_evals(p), 200);
    lib.reset_counters(p);
    EXPECT_EQ(lib.rhs_evals(p), 0);
    if (scene == crest) {
      EXPECT_GT(beyond, 10);  // 36 of 200 with this seed
    }
    lib.close(p);
  }
}

TEST_F(ProblemAbi, LayoutNamesTheFourteenComponents) {
  EXPECT_STREQ(lib.component_name(0), "r00");
  EXPECT_STREQ(lib.component_name(8), "r22");
  EXPECT_STREQ(lib.component_name(kOffsetV), "v0");
  EXPECT_STREQ(lib.component_name(kOffsetAlpha), "x");
  EXPECT_STREQ(lib.component_name(13), "y");
  EXPECT_EQ(lib.component_name(14), nullptr);
  EXPECT_EQ(lib.component_name(-1), nullptr);
}

TEST_F(ProblemAbi, LiftOffAndDomainAreCodesWithTheSuitesReasons) {
  rb_problem* p = lib.open(RB_TEST_DATA "/stop-lift-off.json", 0.0, nullptr, 0);
  ASSERT_NE(p, nullptr);
  // on top of the crest at the start's speed the normal force is negative
  FlatState y;
  ASSERT_EQ(lib.initial_state(p, y.data()), 0);
  y[kOffsetAlpha] = 0.0;
  FlatState dy;
  EXPECT_EQ(lib.rhs(p, 0.0, y.data(), dy.data()), ROLLBENCH_PROBLEM_LIFT_OFF);
  EXPECT_EQ(std::string(lib.message(p)).rfind("the normal force fell to -", 0), 0u) << lib.message(p);
  lib.close(p);

  p = lib.open("valley-sideways", 0.0, nullptr, 0);
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(lib.initial_state(p, y.data()), 0);
  y[kOffsetAlpha] = 1e6;
  EXPECT_EQ(lib.check(p, y.data()), ROLLBENCH_PROBLEM_DOMAIN);
  EXPECT_NE(std::string(lib.message(p)).find("left the domain"), std::string::npos) << lib.message(p);
  y[kOffsetAlpha] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(lib.rhs(p, 0.0, y.data(), dy.data()), ROLLBENCH_PROBLEM_DIVERGED);
  EXPECT_EQ(lib.rhs(p, 0.0, nullptr, dy.data()), ROLLBENCH_PROBLEM_BAD_ARGUMENT);
  EXPECT_EQ(lib.jacobian(p, 0.0, y.data(), nullptr), ROLLBENCH_PROBLEM_BAD_ARGUMENT);
  lib.close(p);
  EXPECT_EQ(lib.rhs(nullptr, 0.0, y.data(), dy.data()), ROLLBENCH_PROBLEM_BAD_ARGUMENT);
  EXPECT_EQ(lib.rhs_evals(nullptr), -1);
  lib.close(nullptr);
}

// as `rollbench run --t-end`: at most the scene's (chaplygin-valley's is 5)
TEST_F(ProblemAbi, TEndShortensTheScenes) {
  rb_problem* p = lib.open("chaplygin-valley", 1.5, nullptr, 0);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(lib.t_end(p), 1.5);
  lib.close(p);
  p = lib.open("chaplygin-valley", 50.0, nullptr, 0);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(lib.t_end(p), 5.0);
  lib.close(p);
  char error[256];
  EXPECT_EQ(lib.open("chaplygin-valley", -1.0, error, sizeof error), nullptr);
  EXPECT_STREQ(error, "'t_end': the end time must be a finite number >= 0 (0: the scene's)");
}

// The loader's own message (InputError: the file, the key), cut to the buffer.
TEST_F(ProblemAbi, BadScenesAreMessagesNamingTheProblem) {
  char error[512];
  EXPECT_EQ(lib.open("/nonexistent/scene.json", 0.0, error, sizeof error), nullptr);
  std::string expected;
  try {
    load_scene("/nonexistent/scene.json");
  } catch (const InputError& e) {
    expected = e.what();
  }
  EXPECT_EQ(error, expected);
  EXPECT_NE(std::string(error).find("/nonexistent/scene.json"), std::string::npos) << error;

  const std::string path = (std::filesystem::temp_directory_path() / "rb_abi_bad_scene.json").string();
  std::ofstream(path) << R"({"name": "bad", "landscape": "x^2", "ball": {"radius": -1, "mass": 1},
                            "start": {"contact": [0, 0], "omega": [0, 0, 0]}, "t_end": 1})";
  EXPECT_EQ(lib.open(path.c_str(), 0.0, error, sizeof error), nullptr);
  EXPECT_NE(std::string(error).find("'ball.radius'"), std::string::npos) << error;
  std::ofstream(path) << "{ not json";
  EXPECT_EQ(lib.open(path.c_str(), 0.0, error, sizeof error), nullptr);
  EXPECT_EQ(std::string(error).rfind("scene '" + path + "': invalid JSON at byte ", 0), 0u) << error;
  std::remove(path.c_str());

  EXPECT_EQ(lib.open("no-such-scene", 0.0, error, 8), nullptr);
  EXPECT_EQ(std::strlen(error), 7u);  // cut, NUL-terminated
  EXPECT_EQ(lib.open(nullptr, 0.0, error, sizeof error), nullptr);
  EXPECT_STREQ(error, "'scene': no scene given (a shipped scene's name or a scene file's path)");
}

}  // namespace
}  // namespace rb

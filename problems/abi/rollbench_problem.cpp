// librollbench_problem.so: the problem's C ABI (rollbench_problem.h) over
// rb::Problem. Exceptions stop here: every entry point returns a code or NULL.
#include "problems/abi/rollbench_problem.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <string>

#include "problems/input_error.hpp"
#include "problems/jacobian.hpp"
#include "problems/scene.hpp"

#define RB_EXPORT extern "C" __attribute__((visibility("default")))

struct rb_problem {
  rb::Problem problem;
  std::string name;
  std::string message;  // why the last call failed; "" after a success
  long rhs_evals = 0;
  long jacobian_evals = 0;
};

namespace {

// the codes are the report's statuses, so that one cast maps them
static_assert(ROLLBENCH_PROBLEM_DIVERGED == static_cast<int>(rb::Status::diverged));
static_assert(ROLLBENCH_PROBLEM_LIFT_OFF == static_cast<int>(rb::Status::lift_off));
static_assert(ROLLBENCH_PROBLEM_CURVATURE == static_cast<int>(rb::Status::curvature));
static_assert(ROLLBENCH_PROBLEM_DOMAIN == static_cast<int>(rb::Status::domain));
static_assert(ROLLBENCH_PROBLEM_STATE_SIZE == rb::kFlatSize);

constexpr const char* kComponentNames[rb::kFlatSize] = {"r00", "r01", "r02", "r10", "r11", "r12", "r20",
                                                        "r21", "r22", "v0",  "v1",  "v2",  "x",   "y"};

constexpr const char* kDerivedNames[ROLLBENCH_PROBLEM_DERIVED_SIZE] = {
    "cx", "cy", "cz", "wx", "wy", "wz", "energy", "normal_force", "spin", "rotation_defect"};

void write_message(char* buffer, std::size_t size, const std::string& text) {
  if (buffer == nullptr || size == 0) return;
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(buffer, text.data(), n);
  buffer[n] = '\0';
}

int code_of(rb_problem* p, const rb::Validity& v) {
  p->message = v.reason;
  return static_cast<int>(v.status);
}

}  // namespace

RB_EXPORT unsigned rb_problem_abi_version(void) { return ROLLBENCH_PROBLEM_ABI_VERSION; }

RB_EXPORT rb_problem* rb_problem_open(const char* scene, double t_end, char* error, size_t error_size) {
  if (scene == nullptr || !(t_end >= 0.0 && std::isfinite(t_end))) {
    write_message(error, error_size,
                  scene == nullptr
                      ? rb::InputError("no scene given (a shipped scene's name or a scene file's path)", "scene").what()
                      : rb::InputError("the end time must be a finite number >= 0 (0: the scene's)", "t_end").what());
    return nullptr;
  }
  try {
    rb::Scene s = rb::load_scene(scene);
    if (t_end > 0.0) s.t_end = std::min(s.t_end, t_end);  // as `rollbench run --t-end`
    rb_problem* p = new rb_problem{rb::make_problem(s), s.name, {}, 0, 0};
    write_message(error, error_size, "");
    return p;
  } catch (const std::exception& e) {
    // the loader's text, led by the scene where it does not name it (a JSON syntax error)
    std::string what = e.what();
    if (what.find(scene) == std::string::npos) what = "scene '" + std::string(scene) + "': " + what;
    write_message(error, error_size, what);
  } catch (...) {
    write_message(error, error_size, "an unknown error while loading the scene");
  }
  return nullptr;
}

RB_EXPORT void rb_problem_close(rb_problem* problem) { delete problem; }

RB_EXPORT const char* rb_problem_name(const rb_problem* problem) { return problem ? problem->name.c_str() : ""; }

RB_EXPORT int rb_problem_state_size(const rb_problem* problem) { return problem ? rb::kFlatSize : -1; }

RB_EXPORT const char* rb_problem_component_name(int i) {
  return i >= 0 && i < rb::kFlatSize ? kComponentNames[i] : nullptr;
}

RB_EXPORT int rb_problem_initial_state(const rb_problem* problem, double* y0) {
  if (!problem || !y0) return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  for (int i = 0; i < rb::kFlatSize; ++i) y0[i] = problem->problem.y0()[i];
  return ROLLBENCH_PROBLEM_OK;
}

RB_EXPORT double rb_problem_t_end(const rb_problem* problem) {
  return problem ? problem->problem.t_end() : std::numeric_limits<double>::quiet_NaN();
}

RB_EXPORT int rb_problem_rhs(rb_problem* problem, double /*t*/, const double* y, double* dy) {
  if (!problem) return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  if (!y || !dy) {
    problem->message = "y and dy must be arrays of 14 doubles, not NULL";
    return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  }
  ++problem->rhs_evals;
  rb::ModelMargins margins;
  problem->problem.flat_rhs(y, dy, margins);
  // the drivers' test: the reason only when the branch-free one fails
  if (rb::Problem::within_model(margins)) [[likely]] {
    problem->message.clear();
    return ROLLBENCH_PROBLEM_OK;
  }
  return code_of(problem, problem->problem.check_model(margins));
}

RB_EXPORT int rb_problem_jacobian(rb_problem* problem, double /*t*/, const double* y, double* jacobian) {
  if (!problem) return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  if (!y || !jacobian) {
    problem->message = "y must be 14 doubles and jacobian 196, not NULL";
    return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  }
  ++problem->jacobian_evals;
  rb::FlatJacobian J;
  rb::flat_jacobian(problem->problem, Eigen::Map<const rb::FlatState>(y), J);
  std::memcpy(jacobian, J.data(), sizeof(double) * rb::kFlatSize * rb::kFlatSize);
  if (!J.allFinite()) {
    problem->message = "the Jacobian is not finite at this state";
    return ROLLBENCH_PROBLEM_DIVERGED;
  }
  problem->message.clear();
  return ROLLBENCH_PROBLEM_OK;
}

RB_EXPORT int rb_problem_check(rb_problem* problem, const double* y) {
  if (!problem) return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  if (!y) {
    problem->message = "y must be an array of 14 doubles, not NULL";
    return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  }
  const rb::FlatState state = Eigen::Map<const rb::FlatState>(y);
  return code_of(problem, problem->problem.check_full(state));
}

RB_EXPORT int rb_problem_derived(const rb_problem* problem, const double* y, double* derived) {
  if (!problem || !y || !derived) return ROLLBENCH_PROBLEM_BAD_ARGUMENT;
  const rb::Derived d = problem->problem.model().derived(Eigen::Map<const rb::FlatState>(y));
  int n = 0;
  for (int i = 0; i < 3; ++i) derived[n++] = d.centre[i];
  for (int i = 0; i < 3; ++i) derived[n++] = d.omega[i];
  derived[n++] = d.energy;
  derived[n++] = d.normal_force;
  derived[n++] = d.spin;
  derived[n++] = d.rotation_defect;
  return ROLLBENCH_PROBLEM_OK;
}

RB_EXPORT const char* rb_problem_derived_name(int i) {
  return i >= 0 && i < ROLLBENCH_PROBLEM_DERIVED_SIZE ? kDerivedNames[i] : nullptr;
}

RB_EXPORT const char* rb_problem_message(const rb_problem* problem) {
  return problem ? problem->message.c_str() : "no problem (a NULL handle)";
}

RB_EXPORT long rb_problem_rhs_evals(const rb_problem* problem) { return problem ? problem->rhs_evals : -1; }
RB_EXPORT long rb_problem_jacobian_evals(const rb_problem* problem) { return problem ? problem->jacobian_evals : -1; }
RB_EXPORT void rb_problem_reset_counters(rb_problem* problem) {
  if (problem) problem->rhs_evals = problem->jacobian_evals = 0;
}

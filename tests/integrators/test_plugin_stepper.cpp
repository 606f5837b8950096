// Steppers from outside the suite (integrators/steppers/plugin_stepper.hpp): the
// example libraries of examples/ loaded as the CLI's --stepper does, without
// registering them (the registry-wide tests see only the built-in methods).
// A plug-in is driven like a built-in method: the explicit midpoint rule in C
// gives the built-in `midpoint`'s numbers and counts exactly; a broken
// library is refused naming the file and the symbol; a failing step is a
// status.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "integrators/registry.hpp"
#include "integrators/steppers/plugin_stepper.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"
#include "tests/example_steppers.hpp"

namespace rb {
namespace {

using testing::example_stepper;
RunOptions every_quarter(double h, double t_end) {
  RunOptions o;
  o.h = h;
  o.t_end = t_end;
  for (int k = 1; 0.25 * k < t_end; ++k) o.output_times.push_back(0.25 * k);
  return o;
}

PluginIsolation in_process() { return {PluginIsolation::Mode::none, kDefaultIsolatedWallLimit}; }

std::string load_error(const std::string& path) {
  try {
    load_plugin_stepper(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded)";
}

void expect_same_cost(const Cost& a, const Cost& b) {
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.rejected, b.rejected);
  EXPECT_EQ(a.rhs_evals, b.rhs_evals);
  EXPECT_EQ(a.jacobian_evals, b.jacobian_evals);
  EXPECT_EQ(a.validity_checks, b.validity_checks);
}

TEST(PluginStepper, TheExampleDeclaresItsFacts) {
  const std::unique_ptr<Integrator> m = load_plugin_stepper(example_stepper("midpoint_stepper"));
  EXPECT_EQ(m->name(), "midpoint-plugin");
  EXPECT_EQ(m->family(), "plugin");
  EXPECT_EQ(m->declared_order(), 2);
  EXPECT_FALSE(m->adaptive());
  EXPECT_EQ(m->description(),
            "explicit midpoint rule in C, loaded with --stepper (examples/midpoint_stepper.c) "
            "(plug-in, flat view, " +
                example_stepper("midpoint_stepper") + ")");
}

TEST(PluginStepper, GivesTheBuiltInMidpointsNumbersAndCounts) {
  const std::unique_ptr<Integrator> plugin = load_plugin_stepper(example_stepper("midpoint_stepper"));
  for (const char* scene : {"valley-sideways", "chaplygin-valley"}) {
    const Problem problem = make_problem(load_scene(scene));
    const RunOptions o = every_quarter(1.0 / 64.0, 2.0);
    const RunResult a = plugin->integrate(problem, o);
    const RunResult b = find_integrator("midpoint").integrate(problem, o);
    ASSERT_EQ(a.status, Status::ok) << scene << ": " << a.message;
    ASSERT_EQ(a.output.t, b.output.t);
    for (std::size_t i = 0; i < a.output.y.size(); ++i)
      for (int j = 0; j < kFlatSize; ++j)
        EXPECT_EQ(a.output.y[i][j], b.output.y[i][j]) << scene << " t = " << a.output.t[i];
    expect_same_cost(a.cost, b.cost);
    EXPECT_EQ(a.cost.rhs_evals, 2 * a.cost.steps);
    EXPECT_EQ(a.cost.steps, 128);
  }
}

TEST(PluginStepper, TheLieGroupExampleKeepsROnSo3AndCountsItsExponentials) {
  const std::unique_ptr<Integrator> plugin = load_plugin_stepper(example_stepper("lie_euler_stepper"));
  EXPECT_EQ(plugin->declared_order(), 1);
  const Problem problem = make_problem(load_scene("chaplygin-valley"));  // R feeds back into the motion
  const RunOptions o = every_quarter(1.0 / 256.0, 2.0);
  const RunResult a = plugin->integrate(problem, o);
  const RunResult b = find_integrator("exp-euler").integrate(problem, o);
  ASSERT_EQ(a.status, Status::ok) << a.message;
  EXPECT_EQ(a.cost.steps, 512);
  EXPECT_EQ(a.cost.rhs_evals, a.cost.steps);
  EXPECT_EQ(a.cost.exp_evals, a.cost.steps);
  EXPECT_EQ(a.cost.dexpinv_evals, 0);
  EXPECT_LT(rotation_defect(rotation_of(a.final_state)), 1e-13);
  // the same method as the built-in exp-euler, up to the order of the sums
  EXPECT_LT((a.final_state - b.final_state).lpNorm<Eigen::Infinity>(), 1e-12);
}

TEST(PluginStepper, TheCallbacksEvaluateTheProblemAndCountEachCall) {
  const Problem problem = make_problem(load_scene("chaplygin-valley"));
  Cost cost;
  PluginCallContext context{&problem, &cost};
  const rollbench_problem p = plugin_callbacks(context);
  const FlatState y = problem.y0();
  FlatState dy, expected_dy;
  p.flat_rhs(p.context, y.data(), dy.data());
  problem.flat_rhs(y.data(), expected_dy.data());
  EXPECT_EQ(dy, expected_dy);
  double omega[3], dz[5], expected_omega[3], expected_dz[5];
  p.lie_rhs(p.context, y.data(), y.data() + kOffsetV, omega, dz);
  problem.lie_rhs(rotation_of(y), y.data() + kOffsetV, expected_omega, expected_dz);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(omega[i], expected_omega[i]);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(dz[i], expected_dz[i]);
  const Vec3 u(0.3, -0.2, 0.1), w(1.0, 2.0, -0.5);
  double R[9], out[3];
  p.so3_exp(p.context, u.data(), R);
  EXPECT_EQ(Mat3(Eigen::Map<const RowMajorMat3>(R)), so3_exp(u));
  p.so3_dexpinv(p.context, u.data(), w.data(), out);
  EXPECT_EQ(Vec3(Eigen::Map<const Vec3>(out)), dexpinv(u, w));
  EXPECT_EQ(cost.rhs_evals, 2);
  EXPECT_EQ(cost.exp_evals, 1);
  EXPECT_EQ(cost.dexpinv_evals, 1);
}

TEST(PluginStepper, AnErrorCodeIsAFailedRunWithThePluginsMessage) {
  const std::unique_ptr<Integrator> plugin = load_plugin_stepper(example_stepper("fails_stepper"));
  const Problem problem = make_problem(load_scene("valley-sideways"));
  const RunOptions o = every_quarter(1.0 / 16.0, 2.0);
  const RunResult run = plugin->integrate(problem, o);
  EXPECT_EQ(run.status, Status::error);
  EXPECT_EQ(run.message,
            "stepper 'fails-stepper' returned error code 7 at t = 0.5: the linear solve did not converge (residual "
            "1.0e-03)");
  // it ends at the last valid state, with every output up to it
  EXPECT_EQ(run.stop_time, 0.5);
  EXPECT_EQ(run.output.t, (std::vector<double>{0.25, 0.5}));
  const RunResult midpoint = find_integrator("midpoint").integrate(problem, every_quarter(1.0 / 16.0, 0.5));
  EXPECT_EQ(run.final_state, midpoint.final_state);
  EXPECT_EQ(run.cost.steps, 8);  // the failed attempt is not an accepted step (as for a failed GSL step)
}

TEST(PluginStepper, ANonFiniteStateIsTheUsualDivergedStatus) {
  const std::unique_ptr<Integrator> plugin = load_plugin_stepper(example_stepper("nan_stepper"));
  const RunResult run = plugin->integrate(make_problem(load_scene("valley-sideways")), every_quarter(1.0 / 16.0, 2.0));
  EXPECT_EQ(run.status, Status::diverged);
  EXPECT_EQ(run.stop_time, 0.5);
  EXPECT_TRUE(run.final_state.allFinite());
}

TEST(PluginStepper, AnIsolatedRunReturnsWhatTheInProcessRunReturns) {
  const Problem problem = make_problem(load_scene("chaplygin-valley"));
  const RunOptions o = every_quarter(1.0 / 64.0, 2.0);
  for (const char* name : {"midpoint_stepper", "lie_euler_stepper", "fails_stepper"}) {
    const RunResult a = load_plugin_stepper(example_stepper(name))->integrate(problem, o);  // a child process
    const RunResult b = load_plugin_stepper(example_stepper(name), in_process())->integrate(problem, o);
    EXPECT_EQ(a.status, b.status) << name;
    EXPECT_EQ(a.message, b.message) << name;
    EXPECT_EQ(a.stop_time, b.stop_time) << name;
    EXPECT_EQ(a.final_state, b.final_state) << name;
    ASSERT_EQ(a.output.t, b.output.t) << name;
    for (std::size_t i = 0; i < a.output.y.size(); ++i) EXPECT_EQ(a.output.y[i], b.output.y[i]) << name;
    expect_same_cost(a.cost, b.cost);
    EXPECT_EQ(a.cost.exp_evals, b.cost.exp_evals) << name;
    // the child timed its own integration; in-process the caller times it
    EXPECT_TRUE(std::isfinite(a.solve_seconds) && a.solve_seconds >= 0.0) << name;
    EXPECT_TRUE(std::isnan(b.solve_seconds)) << name;
  }
}

TEST(PluginStepper, ACrashAnAbortAndAHangAreStatusesOfTheRun) {
  const Problem problem = make_problem(load_scene("valley-sideways"));
  const RunOptions o = every_quarter(1.0 / 16.0, 2.0);
  const PluginIsolation one_second{PluginIsolation::Mode::process, 1.0};
  const RunResult crash = load_plugin_stepper(example_stepper("crash_stepper"), one_second)->integrate(problem, o);
  EXPECT_EQ(crash.status, Status::crashed);
  EXPECT_EQ(crash.message,
            "stepper 'crash-stepper' crashed: its process was killed by signal 11 (SIGSEGV: Segmentation fault); its "
            "state and cost are lost");
  EXPECT_EQ(crash.stop_time, 0.0);
  EXPECT_EQ(crash.final_state, problem.y0());
  const RunResult abort = load_plugin_stepper(example_stepper("abort_stepper"), one_second)->integrate(problem, o);
  EXPECT_EQ(abort.status, Status::crashed);
  EXPECT_EQ(abort.message,
            "stepper 'abort-stepper' crashed: its process was killed by signal 6 (SIGABRT: Aborted); its state and "
            "cost are lost");
  const RunResult hang = load_plugin_stepper(example_stepper("hang_stepper"), one_second)->integrate(problem, o);
  EXPECT_EQ(hang.status, Status::timeout);
  EXPECT_EQ(hang.message,
            "stepper 'hang-stepper' was still running after the wall-clock limit of 1 s (--stepper-timeout) and was "
            "killed; its state and cost are lost");
  EXPECT_EQ(hang.final_state, problem.y0());
}

TEST(PluginStepper, AnInputErrorInTheChildIsThrownAgainInTheParent) {
  RunOptions o = every_quarter(1.0 / 16.0, 2.0);
  o.h = 0.0;  // no step: the fixed-step driver in the child refuses it
  const Problem problem = make_problem(load_scene("valley-sideways"));
  for (const PluginIsolation& isolation : {PluginIsolation{}, in_process()}) {
    try {
      load_plugin_stepper(example_stepper("midpoint_stepper"), isolation)->integrate(problem, o);
      ADD_FAILURE() << "h = 0 was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "h");
      EXPECT_EQ(std::string(e.what()), "'h': a fixed-step method needs a step h > 0");
    }
  }
}

TEST(PluginStepper, ALieViewStateOffSo3IsTheStatusOffGroup) {
  const Problem problem = make_problem(load_scene("valley-sideways"));
  const RunOptions o = every_quarter(1.0 / 16.0, 2.0);
  for (const PluginIsolation& isolation : {PluginIsolation{}, in_process()}) {
    const RunResult run = load_plugin_stepper(example_stepper("off_group_stepper"), isolation)->integrate(problem, o);
    EXPECT_EQ(run.status, Status::off_group);
    // R scaled by 1.1: R^T R - I = 0.21 I, whose Frobenius norm is 0.21 sqrt(3)
    EXPECT_EQ(run.message,
              "stepper 'off-group-stepper' (Lie-group view) returned R off SO(3) in the step from t = 0.5: "
              "||R^T R - I||_F = 0.364 > 1e-06");
    EXPECT_EQ(run.stop_time, 0.5);
    EXPECT_LT(rotation_defect(rotation_of(run.final_state)), 1e-13);  // the last state on the group
    EXPECT_EQ(run.output.t, (std::vector<double>{0.25, 0.5}));
  }
  // an honest Lie-view method's rounding stays far inside the bound over
  // many steps, and a flat method's drift is not held to it
  RunOptions many = every_quarter(1e-4, 2.0);
  const RunResult honest = load_plugin_stepper(example_stepper("lie_euler_stepper"))->integrate(problem, many);
  EXPECT_EQ(honest.status, Status::ok) << honest.message;
  EXPECT_LT(rotation_defect(rotation_of(honest.final_state)), 1e-3 * kOffGroupBound);
  const RunResult flat =
      load_plugin_stepper(example_stepper("midpoint_stepper"))->integrate(problem, every_quarter(0.25, 2.0));
  EXPECT_EQ(flat.status, Status::ok) << flat.message;
  EXPECT_GT(rotation_defect(rotation_of(flat.final_state)), kOffGroupBound);
}

TEST(PluginStepper, AFolderIsNamedAsOne) {
  const std::string folder = std::filesystem::temp_directory_path().string();
  EXPECT_EQ(load_error(folder),
            "'stepper': '" + folder + "' is a directory, not a stepper library (give the .so file in it)");
  EXPECT_EQ(load_error("/dev/null"),
            "'stepper': '/dev/null' is not a regular file (a device, FIFO or socket), not a stepper library");
}

TEST(PluginStepper, ABrokenLibraryIsRefusedNamingTheFileAndTheSymbol) {
  const std::string missing = example_stepper("no_such_stepper");
  EXPECT_EQ(load_error(missing), "'stepper': '" + missing + "': no such file");
  const std::string no_step = example_stepper("no_step_stepper");
  EXPECT_EQ(load_error(no_step), "'stepper': '" + no_step +
                                     "' does not export 'rollbench_stepper_step' (see "
                                     "integrators/plugin/rollbench_stepper.h)");
  const std::string bad_abi = example_stepper("bad_abi_stepper");
  EXPECT_EQ(load_error(bad_abi), "'stepper': '" + bad_abi +
                                     "': rollbench_stepper_abi_version() is 99, this rollbench takes 1 (rebuild it "
                                     "against integrators/plugin/rollbench_stepper.h)");
  const std::string bad_order = example_stepper("bad_order_stepper");
  EXPECT_EQ(load_error(bad_order), "'stepper': '" + bad_order +
                                       "': rollbench_stepper_info(): the order of 'bad-order-stepper' is 0, not >= 1");
  const std::string bad_name = example_stepper("bad_name_stepper");
  EXPECT_EQ(load_error(bad_name), "'stepper': '" + bad_name +
                                      "': rollbench_stepper_info(): the name 'bad name' may hold only letters, digits "
                                      "and . _ + -");
  // a file that is not a shared object: dlopen's reason follows
  const std::string text =
      (std::filesystem::temp_directory_path() / ("rb-plugin-" + std::to_string(::getpid()) + "-not-a-library.so"))
          .string();
  std::ofstream(text) << "not an ELF file\n";
  EXPECT_EQ(load_error(text).rfind("'stepper': '" + text + "' is not a shared library that can be loaded (", 0), 0u)
      << load_error(text);
  std::filesystem::remove(text);
}

}  // namespace
}  // namespace rb

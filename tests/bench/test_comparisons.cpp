// Comparisons that measure what they claim: errors that see R (error.worst,
// error_max), the timed call's outputs (--dt-out does not set an adaptive
// method's steps) and tolerance fits; the stability study is tested in
// test_stability.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/lib/order_fit.hpp"
#include "bench/lib/report.hpp"
#include "integrators/registry.hpp"

namespace rb {
namespace {

SweepSpec one_scene(const std::string& scene, double t_end) {
  SweepSpec spec = preset("quick");
  spec.scenes = {scene};
  spec.t_end = t_end;
  spec.repeats = 0;
  return spec;
}

RunRecord run_one(const SweepScene& s, const std::string& method, double h, double tol = kNaN) {
  const Tolerances tolerances = std::isnan(tol) ? Tolerances() : Tolerances(tol, tol);
  return run_task(s, SweepTask{0, 0, method, h, tolerances, nullptr}, 5'000'000);
}

// rkmk8 and odeint-fehlberg78 share a tableau and, for a homogeneous ball
// whose R never feeds back, the same contact point to rounding: only an
// error that sees R can tell them apart.
TEST(Comparisons, WorstErrorTellsApartMethodsWhoseContactErrorsAgree) {
  const std::vector<SweepScene> scenes = prepare_scenes(one_scene("bumpy-long", 0.0));
  const SweepScene& s = scenes.front();
  const RunRecord lie = run_one(s, "rkmk8", 0.25), flat = run_one(s, "odeint-fehlberg78", 0.25);
  ASSERT_EQ(lie.status, Status::ok);
  ASSERT_EQ(flat.status, Status::ok);
  ASSERT_TRUE(std::isfinite(lie.error.contact) && std::isfinite(flat.error.contact));
  EXPECT_NEAR(lie.error.contact, flat.error.contact, 1e-5 * flat.error.contact);
  const double ratio = lie.error.rotation / flat.error.rotation;
  EXPECT_TRUE(ratio > 2.0 || ratio < 0.5) << lie.error.rotation << " vs " << flat.error.rotation;
  const double worst_ratio = lie.error.worst / flat.error.worst;
  EXPECT_TRUE(worst_ratio > 2.0 || worst_ratio < 0.5) << lie.error.worst << " vs " << flat.error.worst;
  // worst is the largest of the scaled components
  const double r = s.problem.model().params().radius;
  for (const RunRecord* x : {&lie, &flat}) {
    EXPECT_GE(x->error.worst, x->error.contact / r);
    EXPECT_GE(x->error.worst, x->error.centre / r);
    EXPECT_GE(x->error.worst, x->error.rotation);
    EXPECT_GE(x->error.worst, x->error.omega / s.omega_scale);
  }
}

TEST(Comparisons, ErrorMaxCoversTheGridAndBoundsTheErrorAtTheEnd) {
  const std::vector<SweepScene> scenes = prepare_scenes(one_scene("valley-sideways", 2.0));
  const SweepScene& s = scenes.front();
  ASSERT_EQ(s.times.size(), 8u);  // every 0.25 up to 2
  ASSERT_EQ(s.timed_times, std::vector<double>{2.0});
  for (const auto& [method, h, tol] : {std::tuple{"rk4", 0.0625, kNaN},
                                       {"rk4", 0.5, kNaN},
                                       {"odeint-dopri5-adaptive", kNaN, 1e-6},
                                       {"gsl-rkf45-adaptive", kNaN, 1e-6}}) {
    const RunRecord x = run_one(s, method, h, tol);
    ASSERT_EQ(x.status, Status::ok) << method;
    EXPECT_EQ(x.error.points, 1);
    EXPECT_EQ(x.timed_outputs, 1u) << "the timed call records t_end only";
    // a method that lands on each output takes other steps on the grid:
    // its error_max is the timed run's own (t_end), the grid run's beside it
    const bool lands = std::string(method) == "gsl-rkf45-adaptive";
    EXPECT_EQ(x.error_max_source.same_steps, !lands) << method;
    EXPECT_EQ(x.has_error_grid, lands) << method;
    // a fixed step of 0.5 is measured at the grid's multiples of 0.5
    EXPECT_EQ(x.error_max.points, lands ? 1 : h == 0.5 ? 4 : 8) << method;
    if (lands) {
      EXPECT_EQ(x.error_grid.points, 8) << method;
    }
    // from the timed run's steps, never below the error at its end
    EXPECT_GE(x.error_max.worst, x.error.worst) << method;
    EXPECT_GE(x.error_max.rotation, x.error.rotation) << method;
    EXPECT_GE(x.error_max.contact, x.error.contact) << method;
  }
}

// A dense-output method's steps are its controller's alone: recording
// outputs coarser than its steps, or none but t_end, does not change them.
TEST(Comparisons, AnAdaptiveMethodsStepsDoNotDependOnACoarserOutputGrid) {
  for (const char* method : {"odeint-dopri5-adaptive", "rkmk-dp54-adaptive"}) {
    std::vector<long> steps;
    for (const double dt_out : {0.0, 2.5, 1.25}) {
      SweepSpec spec = one_scene("bowl-3d", 5.0);
      spec.dt_out = dt_out;
      const std::vector<SweepScene> scenes = prepare_scenes(spec);
      const RunRecord x = run_one(scenes.front(), method, kNaN, 1e-8);
      ASSERT_EQ(x.status, Status::ok) << method;
      EXPECT_LT(5.0 / static_cast<double>(x.cost.steps), 0.5) << "its steps are finer than the outputs";
      EXPECT_TRUE(x.error_max_source.same_steps) << method << ", dt_out " << dt_out;
      steps.push_back(x.cost.steps);
    }
    EXPECT_EQ(steps[0], steps[1]) << method;
    EXPECT_EQ(steps[0], steps[2]) << method;
  }
  // a method that lands on every output takes more steps on a grid; the
  // timed call, asked for t_end only, does not pay them
  const std::vector<SweepScene> scenes = prepare_scenes(one_scene("bowl-3d", 5.0));
  const RunRecord x = run_one(scenes.front(), "odeint-fehlberg78-adaptive", kNaN, 1e-4);
  RunOptions end_only;
  end_only.tolerances = Tolerances(1e-4, 1e-4);
  const RunResult alone = find_integrator("odeint-fehlberg78-adaptive").integrate(scenes.front().problem, end_only);
  EXPECT_EQ(x.cost.steps, alone.cost.steps);
  EXPECT_GT(x.error_max_source.steps, x.cost.steps);
  EXPECT_FALSE(x.error_max_source.same_steps);
}

TEST(Comparisons, TheTimedCallOfEveryMethodRecordsTheSameOutputs) {
  SweepSpec spec = one_scene("valley-sideways", 2.0);
  spec.dt_out = 0.5;
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  for (const auto& [method, h, tol] :
       {std::tuple{"rk4", 0.125, kNaN}, {"rkmk4", 0.25, kNaN}, {"odeint-fehlberg78-adaptive", kNaN, 1e-6}}) {
    const RunRecord x = run_one(scenes.front(), method, h, tol);
    EXPECT_EQ(x.timed_outputs, 4u) << method;
    EXPECT_TRUE(x.error_max_source.same_steps) << method << ": the timed call records the error grid itself";
  }
}

TEST(Comparisons, ToleranceFitsOfAdaptiveMethods) {
  SweepSpec spec = one_scene("valley-sideways", 2.0);
  spec.integrators = {"odeint-dopri5-adaptive", "rk4"};
  spec.tols = {1e-4, 1e-6, 1e-8};
  spec.hs = {0.1};
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  const auto quiet = [](const std::string&) {};
  const nlohmann::json report = make_report(spec, scenes, run_sweep(spec, scenes, quiet), {});
  ASSERT_EQ(report["tolerance_fits"].size(), 1u) << "fixed-step methods have no tolerance";
  const nlohmann::json& fit = report["tolerance_fits"][0];
  EXPECT_EQ(fit["integrator"], "odeint-dopri5-adaptive");
  EXPECT_EQ(fit["points"], 3);
  // a 5th-order method's error falls with the tolerance, at most in proportion
  const double slope = fit["slope"].get<double>();
  EXPECT_GT(slope, 0.5);
  EXPECT_LT(slope, 1.5);
  // the fit is the least-squares line of its runs' points
  std::vector<double> x, y;
  for (const nlohmann::json& run : report["runs"])
    if (run["adaptive"].get<bool>()) {
      x.push_back(std::log10(run["rtol"].get<double>()));
      y.push_back(std::log10(run["error"]["worst"].get<double>()));
    }
  EXPECT_NEAR(slope, fit_line(x, y).slope, 1e-12);
}

}  // namespace
}  // namespace rb

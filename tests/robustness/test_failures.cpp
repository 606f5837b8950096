// Failing methods (docs/bad-input.md): one method of every family and driver in the
// registry is driven into each failure it can have. Each run must end with
// the right status and a reason, stop at the time it reached, keep every
// row before the stop, and a sweep over the failing cases must record every
// run. The registry is read, never listed: a new family is tested as soon
// as it registers.
#include <cmath>
#include <string>

#include "bench/lib/report.hpp"
#include "bench/lib/sweep.hpp"
#include "tests/registry_names.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb::robustness {
namespace {

constexpr double kDt = 0.01;  // output spacing: the full checks run at outputs

// The promises of integrator.hpp for a run that stopped early.
void expect_stopped(const Problem& p, const RunOptions& o, const RunResult& r, Status want, bool moved,
                    const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(status_name(r.status), status_name(want)) << r.message;
  EXPECT_FALSE(r.message.empty());
  EXPECT_LT(r.stop_time, o.t_end);
  if (moved) {
    EXPECT_GT(r.stop_time, 0.0);
  }
  EXPECT_TRUE(r.final_state.allFinite());
  // every output before the stop is kept, valid, and none after it
  std::size_t before = 0, up_to = 0;
  for (const double t : o.output_times) {
    before += t < r.stop_time;
    up_to += t <= r.stop_time;
  }
  EXPECT_GE(r.output.t.size(), before);
  EXPECT_LE(r.output.t.size(), up_to);
  for (std::size_t i = 0; i < r.output.t.size(); ++i) {
    EXPECT_EQ(r.output.t[i], o.output_times[i]);
    EXPECT_EQ(p.check_full(r.output.y[i]).status, Status::ok) << "row at t = " << r.output.t[i];
  }
}

struct StopCase {
  const char* file;
  Status status;
};

// tests/data: each scene leaves the model's validity in its own way
const StopCase kStopScenes[] = {{"stop-nonfinite.json", Status::diverged},
                                {"stop-lift-off.json", Status::lift_off},
                                {"stop-curvature.json", Status::curvature},
                                {"stop-domain.json", Status::domain}};

class FamilyFailures : public ::testing::TestWithParam<std::string> {
 protected:
  const Integrator& method() const { return find_integrator(GetParam()); }
};

std::vector<std::string> representatives() {
  std::vector<std::string> names;
  for (const Integrator* m : one_per_family_and_driver()) names.push_back(m->name());
  return names;
}

std::vector<std::string> adaptive_representatives() {
  std::vector<std::string> names;
  for (const Integrator* m : one_per_family_and_driver())
    if (m->adaptive()) names.push_back(m->name());
  return names;
}

TEST_P(FamilyFailures, LeavingTheModelEndsWithItsStatus) {
  const Integrator& m = method();
  for (const StopCase& c : kStopScenes) {
    const Problem p = data_problem(c.file);
    const RunOptions o = options_for(m, p.t_end(), 1e-3, 1e-8, kDt);
    const RunResult r = m.integrate(p, o);
    expect_stopped(p, o, r, c.status, true, m.name() + " on " + c.file);
    EXPECT_GE(r.output.t.size(), 10u) << m.name() << " on " << c.file;
  }
}

TEST_P(FamilyFailures, StepBudgetEndsWithMaxSteps) {
  const Integrator& m = method();
  const Problem p = make_problem(load_scene("valley-sideways"));
  RunOptions o = options_for(m, 1.0, kDt, 1e-6, kDt);
  o.max_steps = 3;
  const RunResult r = m.integrate(p, o);
  expect_stopped(p, o, r, Status::max_steps, !m.adaptive(), m.name());
  EXPECT_EQ(r.message, "reached max_steps = 3");
  EXPECT_LE(r.cost.steps, 3);
  if (!m.adaptive()) {
    EXPECT_EQ(r.stop_time, 3 * kDt);
    EXPECT_EQ(r.output.t.size(), 3u);
  }
}

// fixed-step methods have no tolerance to refuse
class AdaptiveFailures : public FamilyFailures {};

TEST_P(AdaptiveFailures, ToleranceBelowRoundingIsStepUnderflow) {
  const Integrator& m = method();
  const Problem p = make_problem(load_scene("valley-sideways"));
  const RunOptions o = options_for(m, 1.0, 0.0, 1e-18, kDt);
  const RunResult r = m.integrate(p, o);
  // refused at the start: no step can meet it, so none is taken
  expect_stopped(p, o, r, Status::step_underflow, false, m.name());
  EXPECT_EQ(r.stop_time, 0.0);
  EXPECT_EQ(r.final_state, p.y0());
}

INSTANTIATE_TEST_SUITE_P(EveryFamily, FamilyFailures, ::testing::ValuesIn(representatives()),
                         rb::testing::registry_test_name);
INSTANTIATE_TEST_SUITE_P(EveryAdaptiveFamily, AdaptiveFailures, ::testing::ValuesIn(adaptive_representatives()),
                         rb::testing::registry_test_name);

// A trial step that overshoots the landscape's edge (x > 1 in
// stop-nonfinite, reached near t = 1.29) gives a non-finite error estimate:
// that is a step too large, to be rejected and shrunk, not the method's end.
// A method that stops at the first such trial reports a failure time far
// before the true one, and the benchmark would blame it for the landscape.
TEST(FamilyFailures, AdaptiveMethodsShrinkANonFiniteTrialStep) {
  const Problem p = data_problem("stop-nonfinite.json");
  for (const auto& m : registry()) {
    if (!m->adaptive()) continue;
    for (const double tol : {1e-6, 1e-8}) {
      const RunResult r = m->integrate(p, options_for(*m, p.t_end(), 0.0, tol, kDt));
      EXPECT_NE(r.status, Status::ok) << m->name();
      EXPECT_GT(r.stop_time, 1.2) << m->name() << " tol " << tol << " gave up early: " << status_name(r.status) << ": "
                                  << r.message;
    }
  }
}

// Found by fuzz_run (fuzz/corpus/fuzz_run/regress-dense-nonfinite.json): a
// dense output can go non-finite between two finite step ends; the run must
// then end on the last valid state, not on the interpolant. Short runs as the
// fuzzer makes them: every adaptive method, tolerances, given first steps.
TEST(FamilyFailures, ANonFiniteDenseOutputEndsOnTheLastValidState) {
  const Problem p = data_problem("regress-dense-nonfinite.json");
  int stopped = 0;
  for (const auto& m : registry()) {
    if (!m->adaptive()) continue;
    for (const double tol : {1e-3, 1e-6, 1e-9, 1e-13}) {
      for (int k = 0; k <= 64; ++k) {
        RunOptions o = options_for(*m, 0.5, 0.0, tol, 0.125);
        o.h = k == 0 ? 0.0 : 0.5 / k;
        o.max_steps = 60;
        const RunResult r = m->integrate(p, o);
        if (r.status == Status::ok) continue;
        ++stopped;
        ASSERT_TRUE(r.final_state.allFinite())
            << m->name() << " tol " << tol << " h " << o.h << ": " << status_name(r.status) << ": " << r.message;
        for (const FlatState& y : r.output.y) ASSERT_TRUE(y.allFinite()) << m->name();
      }
    }
  }
  EXPECT_GT(stopped, 0) << "the scene no longer makes runs stop";
}

// A library's own error: an implicit method's Newton iteration cannot
// converge over a huge step, and the library says so with an error code;
// the suite's own Newton (gauss, dg2) says so with status solver.
// The first implicit fixed-step method of each family that has one.
TEST(FamilyFailures, LibraryErrorCodeIsStatusError) {
  const Problem p = make_problem(load_scene("valley-sideways"));
  std::vector<std::string> families;
  for (const auto& m : registry()) {
    if (!m->needs_jacobian() || m->adaptive()) continue;
    // the Lie midpoint rule solves its equations even at h = 1e5 and leaves
    // the domain: a model's stop (its Newton's failure: SymmetricMethods.*)
    if (m->info().on_group) continue;
    if (std::find(families.begin(), families.end(), m->family()) != families.end()) continue;
    families.push_back(m->family());
    RunOptions o;
    o.t_end = 1e6;
    o.h = 1e5;
    const RunResult r = m->integrate(p, o);
    expect_stopped(p, o, r, m->family() == "gsl" ? Status::error : Status::solver, false, m->name());
    EXPECT_NE(r.message.find(m->family() == "gsl" ? "GSL_" : ""), std::string::npos) << r.message;
  }
  EXPECT_FALSE(families.empty()) << "no implicit fixed-step method registered";
}

// A sweep over the failing scenes and options: every run is recorded with
// its status and the time it reached, nothing escapes, the report holds them.
TEST(FailingSweep, EveryRunIsRecordedAndNoneCrashes) {
  SweepSpec spec;
  for (const StopCase& c : kStopScenes) spec.scenes.push_back(std::string(RB_TEST_DATA) + "/" + c.file);
  spec.integrators = representatives();
  spec.hs = {1e-2, 0.0};      // 0: no step, which the fixed-step methods refuse
  spec.tols = {1e-6, 1e-18};  // 1e-18: below rounding
  spec.repeats = 1;
  spec.jobs = 2;
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  ASSERT_EQ(scenes.size(), 4u);
  for (const SweepScene& s : scenes) {
    EXPECT_EQ(s.reference.kind, "none") << s.scene.name << ": a reference cannot be made on a failing scene";
    EXPECT_FALSE(s.reference.message.empty());
  }
  const std::size_t tasks = sweep_tasks(spec, scenes).size();
  const std::vector<RunRecord> runs = run_sweep(spec, scenes, [](const std::string&) {});
  ASSERT_EQ(runs.size(), tasks);
  for (const RunRecord& r : runs) {
    SCOPED_TRACE(r.scene + " " + r.method.name + " h=" + std::to_string(r.h) + " tol=" + std::to_string(r.rtol));
    EXPECT_NE(r.status, Status::ok);
    EXPECT_FALSE(r.message.empty());
    EXPECT_EQ(r.wall_samples.size(), 1u);
    const Status want = r.h == 0.0 ? Status::error
                        : r.rtol == 1e-18
                            ? Status::step_underflow
                            : std::find_if(std::begin(kStopScenes), std::end(kStopScenes), [&](const StopCase& c) {
                                return r.scene + ".json" == c.file;
                              })->status;
    EXPECT_EQ(status_name(r.status), status_name(want)) << r.message;
    if (want != Status::error && want != Status::step_underflow) {
      EXPECT_GT(r.stop_time, 0.0);
    }
    EXPECT_TRUE(std::isnan(r.error.contact)) << "no error is measured for a stopped run";
  }
  // a step no method can take is the sweep's input error, as a bad tolerance is
  SweepSpec negative = spec;
  negative.hs = {1e-2, -1.0};
  try {
    (void)sweep_tasks(negative, scenes);
    ADD_FAILURE() << "a sweep took h = -1";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "'h': the step h must be a finite number >= 0 (0: an adaptive method chooses its first step)");
  }
  // the report keeps every failed run with its status, message and stop time
  const nlohmann::json report = make_report(spec, scenes, runs, StabilityResults{});
  ASSERT_EQ(report.at("runs").size(), runs.size());
  for (const auto& run : report.at("runs")) {
    EXPECT_NE(run.at("status"), "ok");
    EXPECT_TRUE(run.contains("stop_time"));
    EXPECT_FALSE(run.at("message").get<std::string>().empty());
  }
}

}  // namespace
}  // namespace rb::robustness

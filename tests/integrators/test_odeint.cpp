// The Boost.Odeint adapters: what is registered, the counts, outputs on the
// requested times (exactly, and accurate where interpolated), the restart of
// Adams-Bashforth-Moulton when h changes, failures as statuses, bad options.
#include <gtest/gtest.h>

#include <thread>

#include "integrators/families/odeint/odeint.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::fixed;
using testing::valley;

RunOptions adaptive(double tol, double t_end, double h0 = 0.0) {
  RunOptions o;
  o.tolerances = Tolerances(tol, tol);
  o.t_end = t_end;
  o.h = h0;
  return o;
}

// outputs every dt before t_end (t_end is always recorded)
void every(RunOptions& o, double dt, double t_end) {
  for (int k = 1; k * dt < t_end - 1e-12; ++k) o.output_times.push_back(k * dt);
}

// rkmk4 at h = 1e-4 on the given outputs: far below every error checked here
RunResult reference(const Problem& p, const RunOptions& like) {
  RunOptions o = like;
  o.h = 1e-4;
  o.tolerances = {};
  return find_integrator("rkmk4").integrate(p, o);
}

TEST(OdeintRegistry, NamesOrdersAndKinds) {
  struct Expected {
    const char* name;
    int order;
    bool adaptive;
  };
  const Expected expected[] = {
      {"odeint-euler", 1, false},
      {"odeint-rk4", 4, false},
      {"odeint-cash-karp54", 5, false},
      {"odeint-dopri5", 5, false},
      {"odeint-fehlberg78", 8, false},
      {"odeint-abm4", 4, false},
      {"odeint-abm5", 5, false},
      {"odeint-dopri5-adaptive", 5, true},
      {"odeint-cash-karp54-adaptive", 5, true},
      {"odeint-fehlberg78-adaptive", 8, true},
      {"odeint-bulirsch-stoer", 8, true},
  };
  for (const Expected& e : expected) {
    const Integrator& m = find_integrator(e.name);
    EXPECT_EQ(m.family(), "odeint") << e.name;
    EXPECT_EQ(m.declared_order(), e.order) << e.name;
    EXPECT_EQ(m.adaptive(), e.adaptive) << e.name;
    EXPECT_FALSE(m.needs_jacobian()) << e.name;
    EXPECT_FALSE(m.description().empty()) << e.name;
  }
}

TEST(OdeintCounters, FixedStepEvaluationsPerStep) {
  struct Expected {
    const char* name;
    long per_step, extra;  // rhs_evals = per_step * steps + extra
  };
  // dopri5 is FSAL: one evaluation at the start, then 6 a step; abm4 takes
  // 3 runge_kutta4 steps (4 each) to start, then 2 a step (PECE)
  const Expected expected[] = {{"odeint-euler", 1, 0},  {"odeint-rk4", 4, 0},         {"odeint-cash-karp54", 6, 0},
                               {"odeint-dopri5", 6, 1}, {"odeint-fehlberg78", 13, 0}, {"odeint-abm4", 2, 6},
                               {"odeint-abm5", 2, 8}};
  for (const Expected& e : expected) {
    const RunResult r = find_integrator(e.name).integrate(valley(), fixed(0.01, 1.0));
    ASSERT_EQ(r.status, Status::ok) << e.name << ": " << r.message;
    EXPECT_EQ(r.cost.steps, 100) << e.name;
    EXPECT_EQ(r.cost.rejected, 0) << e.name;
    EXPECT_EQ(r.cost.rhs_evals, e.per_step * r.cost.steps + e.extra) << e.name;
  }
}

TEST(OdeintCounters, AdaptiveCountsRejectedAttempts) {
  // a first step of 1 on a run of 1 is far too large: the controller rejects
  // it and shrinks; every attempt costs evaluations
  const RunResult ck = find_integrator("odeint-cash-karp54-adaptive").integrate(valley(), adaptive(1e-8, 1.0, 1.0));
  ASSERT_EQ(ck.status, Status::ok) << ck.message;
  EXPECT_GT(ck.cost.rejected, 0);
  // 5 stages an attempt beyond F at the state, which is computed once per
  // accepted state (the last one is never stepped from)
  EXPECT_EQ(ck.cost.rhs_evals, 5 * (ck.cost.steps + ck.cost.rejected) + ck.cost.steps);

  const RunResult dp = find_integrator("odeint-dopri5-adaptive").integrate(valley(), adaptive(1e-8, 1.0, 1.0));
  ASSERT_EQ(dp.status, Status::ok) << dp.message;
  EXPECT_GT(dp.cost.rejected, 0);
  EXPECT_EQ(dp.cost.rhs_evals, 6 * (dp.cost.steps + dp.cost.rejected) + 1);  // FSAL

  // with h = 0 the first step is guessed from two evaluations
  const RunResult guessed = find_integrator("odeint-dopri5-adaptive").integrate(valley(), adaptive(1e-8, 1.0));
  ASSERT_EQ(guessed.status, Status::ok) << guessed.message;
  EXPECT_EQ(guessed.cost.rhs_evals, 6 * (guessed.cost.steps + guessed.cost.rejected) + 1 + 2);
}

TEST(OdeintOutputs, LandExactlyOnTheRequestedTimes) {
  RunOptions o = fixed(0.003, 1.0);  // output spacing 0.1 is not a multiple of h
  every(o, 0.1, 1.0);
  const RunResult ref = reference(valley(), o);
  for (const char* name : {"odeint-rk4", "odeint-abm4", "odeint-dopri5-adaptive", "odeint-cash-karp54-adaptive",
                           "odeint-fehlberg78-adaptive", "odeint-bulirsch-stoer"}) {
    const Integrator& m = find_integrator(name);
    RunOptions run = o;
    if (m.adaptive()) {
      run = adaptive(1e-9, 1.0);
      run.output_times = o.output_times;
    }
    const RunResult r = m.integrate(valley(), run);
    ASSERT_EQ(r.status, Status::ok) << name << ": " << r.message;
    ASSERT_EQ(r.output.t.size(), 10u) << name;
    for (std::size_t i = 0; i < r.output.t.size(); ++i) {
      const double expected_t = i + 1 < r.output.t.size() ? o.output_times[i] : 1.0;
      EXPECT_EQ(r.output.t[i], expected_t) << name;
      // interpolated (dense output) and clamped outputs are as accurate as the end
      const double e = testing::end_errors(valley(), r.output.y[i], ref.output.y[i]).contact;
      EXPECT_LT(e, m.adaptive() ? 1e-7 : 1e-8) << name << " at t = " << r.output.t[i];
    }
    EXPECT_EQ(r.stop_time, 1.0) << name;
  }
}

TEST(OdeintAbm, RestartsWhenTheStepChangesBetweenOutputs) {
  // 0.105 and 0.895 are not multiples of 0.01: drive_fixed_step takes 11 steps
  // of 0.00955 then 90 of 0.00994, and ABM must restart on the new h
  RunOptions odd = fixed(0.01, 1.0);
  odd.output_times = {0.105};
  RunOptions even = fixed(0.01, 1.0);
  even.output_times = {0.25, 0.5, 0.75};  // multiples of h: no restart
  const FlatState ref = reference(valley(), fixed(0.01, 1.0)).final_state;
  for (const char* name : {"odeint-abm4", "odeint-abm5"}) {
    const Integrator& m = find_integrator(name);
    const long start = std::string(name) == "odeint-abm4" ? 6 : 8;  // extra evaluations of one start
    const RunResult plain = m.integrate(valley(), fixed(0.01, 1.0));
    const RunResult r_even = m.integrate(valley(), even);
    const RunResult r_odd = m.integrate(valley(), odd);
    ASSERT_EQ(r_odd.status, Status::ok) << r_odd.message;
    EXPECT_EQ(r_even.cost.rhs_evals, 2 * r_even.cost.steps + start) << name << ": one start only";
    EXPECT_EQ(r_odd.cost.steps, 101) << name;
    EXPECT_EQ(r_odd.cost.rhs_evals, 2 * r_odd.cost.steps + 2 * start) << name << ": restarted once";
    // a history taken at the old h would cost accuracy; a restart keeps it
    const double e_plain = testing::end_errors(valley(), plain.final_state, ref).contact;
    const double e_odd = testing::end_errors(valley(), r_odd.final_state, ref).contact;
    EXPECT_LT(e_odd, 3.0 * e_plain + 1e-13) << name;
  }
}

TEST(OdeintFailures, LiftOffStopsFixedAndAdaptive) {
  const Problem p = make_problem(load_scene(RB_TEST_DATA "/stop-lift-off.json"));
  for (const char* name : {"odeint-rk4", "odeint-dopri5-adaptive", "odeint-cash-karp54-adaptive"}) {
    const Integrator& m = find_integrator(name);
    RunOptions o = m.adaptive() ? adaptive(1e-8, p.t_end()) : fixed(1e-3, p.t_end());
    every(o, 0.01, p.t_end());
    const RunResult r = m.integrate(p, o);
    EXPECT_EQ(r.status, Status::lift_off) << name << ": " << r.message;
    EXPECT_LT(r.stop_time, p.t_end()) << name;
    EXPECT_FALSE(r.message.empty()) << name;
    ASSERT_FALSE(r.output.t.empty()) << name << ": the rows before the stop are kept";
    EXPECT_LE(r.output.t.back(), r.stop_time) << name;
    EXPECT_GT(r.output.t.size(), 10u) << name;
    EXPECT_TRUE(r.final_state.allFinite()) << name;
  }
}

TEST(OdeintFailures, NonFiniteStateIsDiverged) {
  const Problem p = make_problem(load_scene(RB_TEST_DATA "/stop-nonfinite.json"));
  for (const char* name : {"odeint-rk4", "odeint-abm4", "odeint-dopri5-adaptive", "odeint-bulirsch-stoer"}) {
    const Integrator& m = find_integrator(name);
    RunOptions o = m.adaptive() ? adaptive(1e-8, p.t_end()) : fixed(1e-3, p.t_end());
    every(o, 0.01, p.t_end());
    const RunResult r = m.integrate(p, o);
    EXPECT_EQ(r.status, Status::diverged) << name << ": " << r.message;
    EXPECT_LT(r.stop_time, p.t_end()) << name;
    ASSERT_FALSE(r.output.t.empty()) << name;
    EXPECT_LE(r.output.t.back(), r.stop_time) << name;
    EXPECT_TRUE(r.final_state.allFinite()) << name << ": the last valid state";
  }
}

TEST(OdeintFailures, ToleranceBelowRoundingIsStepUnderflowAtTheStart) {
  for (const char* name : {"odeint-dopri5-adaptive", "odeint-cash-karp54-adaptive", "odeint-fehlberg78-adaptive",
                           "odeint-bulirsch-stoer"}) {
    const RunResult r = find_integrator(name).integrate(valley(), adaptive(1e-18, 1.0));
    EXPECT_EQ(r.status, Status::step_underflow) << name << ": " << r.message;
    EXPECT_EQ(r.stop_time, 0.0) << name;
    EXPECT_EQ(r.final_state, valley().y0()) << name;
    EXPECT_NE(r.message.find("rounding"), std::string::npos) << r.message;
  }
  // an absolute tolerance above rounding keeps a small rtol attainable
  RunOptions o = adaptive(1e-18, 1.0);
  o.tolerances = Tolerances(1e-18, 1e-10);
  EXPECT_EQ(find_integrator("odeint-dopri5-adaptive").integrate(valley(), o).status, Status::ok);
}

TEST(OdeintFailures, MaxStepsCountsAcceptedAndRejected) {
  RunOptions o = adaptive(1e-10, 1.0, 1.0);  // the first attempts are rejected
  o.max_steps = 3;
  const RunResult r = find_integrator("odeint-cash-karp54-adaptive").integrate(valley(), o);
  EXPECT_EQ(r.status, Status::max_steps);
  EXPECT_EQ(r.cost.steps + r.cost.rejected, 3);
  EXPECT_LT(r.stop_time, 1.0);
}

TEST(OdeintOptions, BadOptionsThrowInputError) {
  const Integrator& a = find_integrator("odeint-dopri5-adaptive");
  auto key_of = [&](const Integrator& m, const RunOptions& o) {
    try {
      m.integrate(valley(), o);
    } catch (const InputError& e) {
      return e.key();
    }
    return std::string("no error");
  };
  RunOptions none = adaptive(1e-8, 1.0);
  none.tolerances = {};  // no tolerance at all
  EXPECT_EQ(key_of(a, none), "rtol");
  EXPECT_THROW((void)adaptive(1e-8, 1.0, -0.1), InputError);  // a negative first step: refused where it is set
  RunOptions backwards = adaptive(1e-8, 1.0);
  backwards.output_times = {0.5, 0.2};
  EXPECT_EQ(key_of(a, backwards), "output_times");
  EXPECT_EQ(key_of(find_integrator("odeint-rk4"), fixed(0.0, 1.0)), "h");
}

TEST(OdeintThreads, ConcurrentRunsAgree) {
  // integrators are shared: all run state lives in integrate()
  for (const char* name : {"odeint-abm4", "odeint-dopri5-adaptive", "odeint-bulirsch-stoer"}) {
    const Integrator& m = find_integrator(name);
    const RunOptions o = m.adaptive() ? adaptive(1e-9, 1.0) : fixed(0.005, 1.0);
    const RunResult alone = m.integrate(valley(), o);
    std::vector<RunResult> results(4);
    std::vector<std::thread> threads;
    for (RunResult& r : results) threads.emplace_back([&] { r = m.integrate(valley(), o); });
    for (std::thread& t : threads) t.join();
    for (const RunResult& r : results) {
      EXPECT_EQ(r.final_state, alone.final_state) << name;
      EXPECT_EQ(r.cost.rhs_evals, alone.cost.rhs_evals) << name;
    }
  }
}

}  // namespace
}  // namespace rb

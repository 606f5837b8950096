// The stability study (bench/lib/stability.*, stability_verdict.*): each
// rule fails a rung on its own and no accuracy threshold does; the largest
// stable step holds at every smaller step, every first unstable rung is a
// real failure, the study runs to its horizon whatever the scene's t_end,
// and the limit is the same within one ladder step at the horizon and at 4x
// the horizon.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>

#include "bench/lib/presets.hpp"
#include "bench/lib/stability.hpp"

namespace rb {
namespace {

// 401 times over [0, 10] and f at each
std::vector<double> times() {
  std::vector<double> t;
  for (int i = 0; i <= 400; ++i) t.push_back(10.0 * i / 400);
  return t;
}

std::vector<double> series(const std::function<double(double)>& f) {
  std::vector<double> v;
  for (const double t : times()) v.push_back(f(t));
  return v;
}

RungVerdict judge(const std::function<double(double)>& energy, const std::function<double(double)>& defect,
                  Status status = Status::ok) {
  return judge_rung(status, times(), series(energy), series(defect), 10.0, StabilityBounds{});
}

const auto kSmall = [](double) { return 1e-8; };

TEST(StabilityVerdict, EachRuleFailsARungAndNoAccuracyThresholdDoes) {
  const StabilityBounds b;
  // a steady drift to 0.8 of the energy scale, R off SO(3) by 0.45: inaccurate, not unstable
  RungVerdict v = judge([](double t) { return 0.08 * t; }, [](double t) { return 0.045 * t; });
  EXPECT_EQ(v.failure, StabilityFailure::none);
  EXPECT_DOUBLE_EQ(v.energy_error, 0.8);  // the accuracy, reported beside
  EXPECT_DOUBLE_EQ(v.rotation_defect, 0.45);
  EXPECT_NEAR(v.energy_growth.p_early, 1.0, 1e-12);
  EXPECT_NEAR(v.energy_growth.p_late, 1.0, 1e-12);
  // a power law, however steep, is not exponential: p_late = p_early
  v = judge([](double t) { return 1e-6 * std::pow(t, 5.0); }, kSmall);
  EXPECT_NEAR(v.energy_growth.p_late, 5.0, 1e-9);
  EXPECT_EQ(v.failure, StabilityFailure::none);
  // e^t from 1e-7: 2e-3 at the end, far below every bound, and unstable
  v = judge([](double t) { return 1e-7 * std::exp(t); }, kSmall);
  EXPECT_LT(v.energy_error, 3e-3);
  EXPECT_EQ(v.failure, StabilityFailure::energy_growth);
  EXPECT_NEAR(v.energy_growth.p_late, 2.0 * v.energy_growth.p_early, 1e-9);
  v = judge(kSmall, [](double t) { return 1e-7 * std::exp(t); });
  EXPECT_EQ(v.failure, StabilityFailure::defect_growth);
  EXPECT_STREQ(failure_name(v.failure), "defect-growth");
  // the same growth below the floor (rounding) is not judged
  v = judge([](double t) { return 1e-20 * std::exp(t); }, kSmall);
  EXPECT_EQ(v.failure, StabilityFailure::none);
  // a late jump after a flat stretch does not accelerate over both doublings
  v = judge([](double t) { return t < 6.0 ? 1e-6 : 1e-3; }, kSmall);
  EXPECT_EQ(v.failure, StabilityFailure::none);
  // the bounds: just past each
  v = judge([&](double t) { return t < 9.0 ? 0.0 : b.energy_fraction * 1.01; }, kSmall);
  EXPECT_EQ(v.failure, StabilityFailure::energy);
  v = judge([&](double t) { return t < 9.0 ? b.energy_fraction : 0.0; }, kSmall);
  EXPECT_EQ(v.failure, StabilityFailure::none) << "at the bound is within it";
  v = judge(kSmall, [&](double t) { return t < 9.0 ? 0.0 : b.rotation_defect * 1.01; });
  EXPECT_EQ(v.failure, StabilityFailure::rotation_defect);
  // a non-finite value the run did not stop for is past the bound
  v = judge([](double t) { return t < 9.0 ? 0.0 : kNaN; }, kSmall);
  EXPECT_EQ(v.failure, StabilityFailure::energy);
  // a run that stops fails whatever its errors; they are still reported
  v = judge(kSmall, kSmall, Status::chart_limit);
  EXPECT_EQ(v.failure, StabilityFailure::stopped);
  EXPECT_DOUBLE_EQ(v.energy_error, 1e-8);
}

// The stability study of every fixed-step method on the default preset's
// stability scenes, run to the given horizon.
// The ladder of the test below starts at 2^-6, not the preset's 2^-10: the
// smallest rungs cost the most steps (the implicit methods solve a Newton
// system with a Jacobian at each, nine times a step for the sixth-order
// compositions), and at 4x the horizon every fixed-step method of the
// registry from 2^-10 outlasts ctest's limit under the sanitizers. Soundness
// and the horizon's (in)dependence do not depend on where the ladder starts.
constexpr double kTestLadderStart = 1.0 / 64.0;

StabilityResults study(double horizon) {
  SweepSpec spec = preset("default");
  spec.scenes = {};
  spec.integrators = {};  // every fixed-step method of the registry
  spec.stability.search_h_min = kTestLadderStart;
  spec.stability.search_t_end = horizon;
  spec.stability.integrators = {};  // no drift runs: the ladder only
  return run_stability(spec, [](const std::string&) {});
}

// Every rung's verdict follows from its numbers; the ladder doubles from
// h_min and ends at the first unstable rung; h is the last stable one.
void expect_a_sound_ladder(const StableStepRecord& r, const StabilitySpec& st) {
  const std::string who = r.method.name + " on " + r.scene;
  ASSERT_FALSE(r.tried.empty()) << who;
  EXPECT_DOUBLE_EQ(r.horizon, st.search_t_end) << who;
  EXPECT_DOUBLE_EQ(r.tried.front().h, st.search_h_min) << who;
  double largest_stable = kNaN;
  for (std::size_t i = 0; i < r.tried.size(); ++i) {
    const StableStepTry& t = r.tried[i];
    const std::string at = who + " at h = " + std::to_string(t.h);
    if (i > 0) {
      EXPECT_DOUBLE_EQ(t.h, 2 * r.tried[i - 1].h) << at;
    }
    EXPECT_EQ(t.stable, t.failure == StabilityFailure::none) << at;
    EXPECT_EQ(t.stable, i + 1 < r.tried.size() || r.at_limit) << at;
    // a stable rung reached the horizon (beyond bowl-3d's own t_end of 5 s)
    if (t.stable) {
      EXPECT_DOUBLE_EQ(t.stop_time, st.search_t_end) << at;
    }
    // a failure is a real one: its numbers pass its bound
    switch (t.failure) {
      case StabilityFailure::none:
        EXPECT_EQ(t.status, Status::ok) << at;
        EXPECT_LE(t.energy_error, st.bounds.energy_fraction) << at;
        EXPECT_LE(t.rotation_defect, st.bounds.rotation_defect) << at;
        largest_stable = t.h;
        break;
      case StabilityFailure::stopped:
        EXPECT_NE(t.status, Status::ok) << at;
        EXPECT_LT(t.stop_time, st.search_t_end) << at;
        break;
      case StabilityFailure::energy: EXPECT_FALSE(t.energy_error <= st.bounds.energy_fraction) << at; break;
      case StabilityFailure::rotation_defect: EXPECT_FALSE(t.rotation_defect <= st.bounds.rotation_defect) << at; break;
      case StabilityFailure::energy_growth: EXPECT_TRUE(t.energy_growth.exponential) << at; break;
      case StabilityFailure::defect_growth: EXPECT_TRUE(t.defect_growth.exponential) << at; break;
    }
  }
  if (std::isnan(r.h)) {
    EXPECT_TRUE(std::isnan(largest_stable)) << who;
  } else {
    EXPECT_EQ(r.h, largest_stable) << who;
    EXPECT_EQ(r.rotation_defect, r.tried[r.tried.size() - 1 - (r.at_limit ? 0 : 1)].rotation_defect) << who;
  }
}

TEST(Stability, TheLimitIsASoundLadderAndHoldsAtFourTimesTheHorizon) {
  StabilitySpec st = preset("default").stability;
  st.search_h_min = kTestLadderStart;
  const StabilityResults at = study(st.search_t_end), longer = study(4 * st.search_t_end);
  ASSERT_EQ(at.largest_stable_h.size(), longer.largest_stable_h.size());
  ASSERT_GT(at.largest_stable_h.size(), 30u);
  StabilitySpec st4 = st;
  st4.search_t_end = 4 * st.search_t_end;
  std::map<std::string, const StableStepRecord*> by;
  for (const StableStepRecord& r : at.largest_stable_h) {
    expect_a_sound_ladder(r, st);
    by[r.scene + " " + r.method.name] = &r;
  }
  // "none" counts as the rung below h_min
  const auto rung = [&](double h) { return std::isnan(h) ? -1.0 : std::log2(h / st.search_h_min); };
  for (const StableStepRecord& r : longer.largest_stable_h) {
    expect_a_sound_ladder(r, st4);
    const StableStepRecord& short_run = *by.at(r.scene + " " + r.method.name);
    const double moved = rung(short_run.h) - rung(r.h);
    const std::string who = r.method.name + " on " + r.scene;
    // a longer run never makes a method stable at a larger step
    EXPECT_GE(moved, 0.0) << who;
    // order >= 2: the same within one ladder step. Order 1 (euler,
    // exp-euler) is unstable at every h on a conservative motion (its energy
    // grows as e^(c h t)), so its limit falls with the horizon
    if (r.method.declared_order >= 2) {
      EXPECT_LE(moved, 1.0) << who;
    }
  }
  // the cases of issue 30: inaccurate, not unstable
  const auto tried_at = [](const StableStepRecord& r, double h) {
    for (const StableStepTry& t : r.tried)
      if (t.h == h) return t;
    ADD_FAILURE() << r.method.name << " on " << r.scene << ": no rung at h = " << h;
    return StableStepTry{};
  };
  const StableStepTry rk4 = tried_at(*by.at("bowl-3d rk4"), 0.0625);
  EXPECT_TRUE(rk4.stable);
  EXPECT_GT(rk4.rotation_defect, 1e-2);  // the old bound's "unstable"
  EXPECT_TRUE(tried_at(*by.at("bumpy-long odeint-fehlberg78"), 0.25).stable);
  // a Lie-group method keeps R on SO(3) to rounding wherever it is stable
  EXPECT_LT(by.at("bowl-3d rkmk4")->rotation_defect, 1e-12);
  EXPECT_GT(by.at("bowl-3d rk4")->rotation_defect, 1e-6);
}

}  // namespace
}  // namespace rb

// The stability study (bench/lib/stability.*, stability_verdict.*): the
// verdict tells bounded errors, drift (a power of t, or slow exponential
// growth) and the step's own exponential growth apart on made-up series; an
// energy error above its bound is never within the bounds; the
// limits follow from the rungs; on real runs the blow-up step is the same
// at 10, 100 and 1000 s while h*(T) does not rise with T; and
// --stability-horizons is read strictly.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "bench/lib/presets.hpp"
#include "bench/lib/stability.hpp"
#include "problems/input_error.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

using Series = std::function<double(double)>;

// 401 states over [0, horizon], one a step, the energy error and the
// defect from f and g
DriftSeries made_up(double horizon, const Series& energy, const Series& defect) {
  DriftSeries s;
  for (int i = 0; i <= 400; ++i) {
    const double t = horizon * i / 400;
    s.t.push_back(t);
    s.energy.push_back(energy(t));
    s.energy_flat.push_back(energy(t));
    s.defect.push_back(defect(t));
  }
  return s;
}

HorizonVerdict judge(const Series& energy, const Series& defect, bool stopped = false, double horizon = 10.0) {
  return judge_horizon(stopped, made_up(horizon, energy, defect), horizon, horizon / 400, StabilityBounds{});
}

const Series kSmall = [](double) { return 1e-8; };

TEST(StabilityVerdict, BoundedDriftAndExponentialGrowthAreToldApart) {
  const StabilityBounds b;
  const double step = 10.0 / 400;
  // bounded: an oscillating error far below every bound
  HorizonVerdict v = judge([](double t) { return 1e-3 * (1.5 + std::sin(t)); }, kSmall);
  EXPECT_TRUE(v.within());
  EXPECT_EQ(v.blow_up, BlowUp::none);
  EXPECT_TRUE(std::isnan(v.crossed_at));
  // linear drift past the energy bound: drift-limited, not blown up
  v = judge([](double t) { return 0.03 * t; }, kSmall);
  EXPECT_FALSE(v.energy_within);
  EXPECT_TRUE(v.defect_within);
  EXPECT_FALSE(v.within());
  EXPECT_EQ(v.blow_up, BlowUp::none);
  EXPECT_DOUBLE_EQ(v.energy_error, 0.3);
  EXPECT_NEAR(v.crossed_at, 10.0 / 3, step);
  EXPECT_NEAR(v.energy_growth.p_early, 1.0, 1e-12);  // reported beside the verdict
  EXPECT_NEAR(v.energy_growth.p_late, 1.0, 1e-12);
  // a flat method's defect drifting to 1.7 (R shrinking): drift, not blow-up
  v = judge(kSmall, [](double t) { return 0.17 * t; });
  EXPECT_FALSE(v.defect_within);
  EXPECT_EQ(v.blow_up, BlowUp::none);
  // a power law, however steep, past every bound: drift (from 0.1 to 10 takes 200 steps)
  v = judge([](double t) { return 2e-4 * std::pow(t, 5.0); }, kSmall);
  EXPECT_GT(v.energy_error, b.blow_up_energy);
  EXPECT_EQ(v.blow_up, BlowUp::none);
  // exponential growth doubling each step, from rounding: from the bound to
  // past the blow-up bound in 7 steps, the step's own instability
  v = judge([&](double t) { return 1e-16 * std::exp2(t / step); }, kSmall);
  EXPECT_EQ(v.blow_up, BlowUp::energy);
  EXPECT_STREQ(blow_up_name(v.blow_up), "energy-blow-up");
  EXPECT_LE(v.failed_at - v.crossed_at, b.blow_up_steps * step);
  v = judge(kSmall, [&](double t) { return 1e-16 * std::exp2(t / step); });
  EXPECT_EQ(v.blow_up, BlowUp::rotation_defect);
  EXPECT_STREQ(blow_up_name(v.blow_up), "defect-blow-up");
  // slow exponential growth (x 1.06 a step): from the bound to the blow-up
  // bound takes 77 steps: drift, the horizon it takes moves with the step
  v = judge([&](double t) { return 1e-8 * std::exp(0.06 * t / step); }, kSmall);
  EXPECT_GT(v.energy_error, b.blow_up_energy);
  EXPECT_EQ(v.blow_up, BlowUp::none);
  EXPECT_FALSE(v.energy_within);
  // a jump past the blow-up bound with no warning: blown up
  v = judge(kSmall, [&](double t) { return t < 9.0 ? 0.1 : b.blow_up_defect * 1.1; });
  EXPECT_EQ(v.blow_up, BlowUp::rotation_defect);
  EXPECT_DOUBLE_EQ(v.failed_at, 9.0);
  // a non-finite value the run did not stop for is past every bound
  v = judge([](double t) { return t < 9.0 ? 0.0 : kNaN; }, kSmall);
  EXPECT_EQ(v.blow_up, BlowUp::energy);
  EXPECT_FALSE(v.energy_within);
  // a run that stopped within its bounds blew up; its errors are still reported
  v = judge(kSmall, kSmall, true);
  EXPECT_EQ(v.blow_up, BlowUp::stopped);
  EXPECT_DOUBLE_EQ(v.failed_at, 10.0);
  EXPECT_DOUBLE_EQ(v.energy_error, 1e-8);
  // one that drifted out first and stopped 200 steps later failed of its drift
  v = judge([](double t) { return 0.1 * t; }, kSmall, true);
  EXPECT_EQ(v.blow_up, BlowUp::none);
  EXPECT_FALSE(v.within());
  // within blow_up_steps steps of leaving its bound: the step's failure
  v = judge([&](double t) { return t < 10.0 - 5 * step ? 0.0 : 0.2; }, kSmall, true);
  EXPECT_EQ(v.blow_up, BlowUp::stopped);
}

// cf4 at h = 1 on bumpy-long: 45 % of the energy scale off at 10 s, bounded
// at about 1 later: never within the bounds, and no blow-up
TEST(StabilityVerdict, AnEnergyErrorAboveItsBoundIsNeverWithinTheBounds) {
  const StabilityBounds b;
  const HorizonVerdict v = judge([](double t) { return 0.45 * std::min(1.0, t / 5.0); }, kSmall);
  EXPECT_FALSE(v.energy_within);
  EXPECT_FALSE(v.within());
  EXPECT_EQ(v.blow_up, BlowUp::none);
  EXPECT_GT(v.energy_error, b.energy_fraction);
  // at the bound is within it
  EXPECT_TRUE(judge([&](double) { return b.energy_fraction; }, kSmall).within());
  EXPECT_FALSE(judge([&](double) { return b.energy_fraction * 1.01; }, kSmall).within());
}

TEST(StabilityVerdict, EachHorizonReadsOnlyTheStatesUpToIt) {
  const DriftSeries s = made_up(
      1000.0, [](double t) { return 2e-4 * t; }, kSmall);
  const StabilityBounds b;
  EXPECT_TRUE(judge_horizon(false, s, 10.0, 2.5, b).within());
  EXPECT_DOUBLE_EQ(judge_horizon(false, s, 10.0, 2.5, b).energy_error, 2e-3);
  EXPECT_TRUE(judge_horizon(false, s, 100.0, 2.5, b).within());
  const HorizonVerdict last = judge_horizon(false, s, 1000.0, 2.5, b);
  EXPECT_FALSE(last.energy_within);
  EXPECT_EQ(last.blow_up, BlowUp::none);  // linear: drift, at any horizon
  EXPECT_DOUBLE_EQ(last.crossed_at, 502.5);
  EXPECT_DOUBLE_EQ(first_past(s.t, s.energy, b.energy_fraction), 502.5);
}

// A rung made up from its verdicts per horizon.
StableStepTry rung(double h, std::vector<HorizonVerdict> at, double energy_at = kNaN, double defect_at = kNaN,
                   Status status = Status::ok) {
  StableStepTry t;
  t.h = h;
  t.at = std::move(at);
  t.status = status;
  t.energy_crossed_at = energy_at;
  t.defect_crossed_at = defect_at;
  t.stable = t.at.size() == 3 && t.at.back().within();
  return t;
}

HorizonVerdict verdict(double horizon, bool energy_within, bool defect_within, BlowUp blow = BlowUp::none,
                       double energy = 0.01, double defect = 0.01) {
  HorizonVerdict v;
  v.horizon = horizon;
  v.energy_within = energy_within;
  v.defect_within = defect_within;
  v.blow_up = blow;
  v.energy_error = energy;
  v.rotation_defect = defect;
  return v;
}

TEST(StabilityLimits, FollowFromTheRungs) {
  StableStepRecord r;
  r.horizons = {10.0, 100.0, 1000.0};
  const auto ok = [](double T) { return verdict(T, true, true); };
  r.tried = {
      rung(0.125, {ok(10), ok(100), ok(1000)}),
      // the defect crosses at 500 s: out at 1000 s only
      rung(0.25, {ok(10), ok(100), verdict(1000, true, false, BlowUp::none, 0.02, 0.7)}, kNaN, 500.0),
      // the energy crosses at 50 s, the defect at 5 s: the defect is named (first)
      rung(0.5,
           {verdict(10, true, false, BlowUp::none, 0.05, 0.6), verdict(100, false, false, BlowUp::none, 0.3, 1.7),
            verdict(1000, false, false, BlowUp::none, 0.9, 1.7)},
           50.0, 5.0),
      // stopped at 40 s: blown up from 100 s on, within at 10 s
      rung(1.0, {ok(10), verdict(100, true, true, BlowUp::stopped)}, kNaN, kNaN, Status::chart_limit),
      // blown up at once
      rung(2.0, {verdict(10, false, true, BlowUp::stopped, 3.0)}, 1.0, kNaN, Status::domain),
  };
  read_limits(r, 8.0);
  ASSERT_EQ(r.drift_limited.size(), 3u);
  // h*(10 s): 0.5 crossed the defect bound at 5 s
  EXPECT_EQ(r.drift_limited[0].h, 0.25);
  EXPECT_EQ(r.drift_limited[0].next_h, 0.5);
  EXPECT_EQ(r.drift_limited[0].limited_by, "rotation-defect");
  EXPECT_DOUBLE_EQ(r.drift_limited[0].value, 0.6);
  EXPECT_DOUBLE_EQ(r.drift_limited[0].bound, r.bounds.rotation_defect);
  EXPECT_EQ(r.drift_limited[1].h, 0.25);
  EXPECT_EQ(r.drift_limited[1].limited_by, "rotation-defect");  // first in time, though the energy crossed too
  EXPECT_EQ(r.drift_limited[2].h, 0.125);
  EXPECT_EQ(r.drift_limited[2].next_h, 0.25);
  // non-increasing in T
  EXPECT_GE(r.drift_limited[0].h, r.drift_limited[1].h);
  EXPECT_GE(r.drift_limited[1].h, r.drift_limited[2].h);
  // the blow-up step: 2 at 10 s, 1 from 100 s on (it moved)
  ASSERT_EQ(r.blow_up.size(), 3u);
  EXPECT_EQ(r.blow_up[0].h, 2.0);
  EXPECT_EQ(r.blow_up[0].status, Status::domain);
  EXPECT_EQ(r.blow_up[1].h, 1.0);
  EXPECT_EQ(r.blow_up[1].cause, BlowUp::stopped);
  EXPECT_EQ(r.blow_up[2].h, 1.0);  // a blown-up rung stays blown up
  EXPECT_TRUE(r.blow_up_moves);
  EXPECT_FALSE(r.blow_up[0].smallest_tried);
  // the record of before: h*(last horizon)
  EXPECT_EQ(r.h, 0.125);
  EXPECT_EQ(r.horizon, 1000.0);
  EXPECT_FALSE(r.at_limit);

  // every rung blows up: the smallest tried, h* none, limited by the blow-up
  StableStepRecord all;
  all.horizons = {10.0};
  all.tried = {rung(0.5, {verdict(10, true, true, BlowUp::rotation_defect)}),
               rung(1.0, {verdict(10, true, true, BlowUp::stopped)}, kNaN, kNaN, Status::diverged)};
  read_limits(all, 8.0);
  EXPECT_TRUE(std::isnan(all.drift_limited[0].h));
  EXPECT_EQ(all.drift_limited[0].next_h, 0.5);
  EXPECT_EQ(all.drift_limited[0].limited_by, "blow-up");
  EXPECT_EQ(all.drift_limited[0].blow_up, BlowUp::rotation_defect);
  EXPECT_EQ(all.blow_up[0].h, 0.5);
  EXPECT_TRUE(all.blow_up[0].smallest_tried);
  EXPECT_FALSE(all.blow_up_moves);

  // the ladder's top keeps every bound: at_limit, no blow-up step
  StableStepRecord top;
  top.horizons = {10.0};
  top.tried = {rung(8.0, {ok(10)})};
  read_limits(top, 8.0);
  EXPECT_EQ(top.drift_limited[0].h, 8.0);
  EXPECT_TRUE(top.drift_limited[0].at_limit);
  EXPECT_TRUE(std::isnan(top.blow_up[0].h));
}

// rk4 (flat: R leaves SO(3), its step's stability boundary), rkmk4 (Lie:
// the exponential chart's edge) and cf4 on the default preset's stability
// scene where R feeds back, at the default horizons 10, 100 and 1000 s
TEST(Stability, TheBlowUpStepIsTheSameAtEveryHorizonAndHStarDoesNotRise) {
  SweepSpec spec = preset("default");
  spec.integrators = {"rk4", "rkmk4", "cf4"};
  spec.stability.scenes = {"chaplygin-bumpy-long"};
  spec.stability.integrators = {};  // no drift runs: the ladder only
  ASSERT_EQ(spec.stability.horizons, (std::vector<double>{10.0, 100.0, 1000.0}));
  const StabilityResults out = run_stability(spec, [](const std::string&) {});
  ASSERT_EQ(out.largest_stable_h.size(), 3u);
  const StabilityBounds& b = spec.stability.bounds;
  for (const StableStepRecord& r : out.largest_stable_h) {
    const std::string who = r.method.name + " on " + r.scene;
    ASSERT_EQ(r.blow_up.size(), 3u) << who;
    ASSERT_EQ(r.drift_limited.size(), 3u) << who;
    // a real blow-up step, the same rung at every horizon
    EXPECT_TRUE(std::isfinite(r.blow_up[0].h)) << who;
    EXPECT_FALSE(r.blow_up_moves) << who;
    for (const BlowUpStep& s : r.blow_up) EXPECT_EQ(s.h, r.blow_up[0].h) << who << " at " << s.horizon << " s";
    // h*(T) below it and non-increasing in T, each ended by a named quantity
    for (std::size_t k = 0; k < 3; ++k) {
      const DriftLimit& d = r.drift_limited[k];
      EXPECT_LT(d.h, r.blow_up[k].h) << who;
      if (k > 0) {
        EXPECT_LE(d.h, r.drift_limited[k - 1].h) << who << " at " << d.horizon << " s";
      }
      EXPECT_FALSE(d.limited_by.empty()) << who;
      if (d.limited_by != "blow-up") {
        EXPECT_GT(d.value, d.bound) << who;
      }
    }
    // no rung within the bounds at a horizon with an energy error or defect above its bound
    for (const StableStepTry& t : r.tried)
      for (const HorizonVerdict& v : t.at)
        if (v.within()) {
          EXPECT_LE(v.energy_error, b.energy_fraction) << who << " at h = " << t.h;
          EXPECT_LE(v.rotation_defect, b.rotation_defect) << who << " at h = " << t.h;
        }
  }
}

// Every fixed-step method of the registry on one scene at 10 and 100 s:
// each verdict follows from its numbers, h*(T) does not rise with T and
// stays below the blow-up step, and the ladder ends where it says.
TEST(Stability, EveryMethodsLimitsFollowFromItsRuns) {
  SweepSpec spec = preset("default");
  spec.integrators = {};  // every fixed-step method
  spec.stability.scenes = {"bumpy-long"};
  spec.stability.integrators = {};
  spec.stability.horizons = {10.0, 100.0};
  const StabilityResults out = run_stability(spec, [](const std::string&) {});
  ASSERT_GT(out.largest_stable_h.size(), 40u);
  const StabilitySpec& st = spec.stability;
  const StabilityBounds& b = st.bounds;
  for (const StableStepRecord& r : out.largest_stable_h) {
    const std::string who = r.method.name;
    ASSERT_FALSE(r.tried.empty()) << who;
    // downward from the top to the first rung that kept every bound, or the bottom
    EXPECT_EQ(r.tried.back().h, st.search_h_max) << who;
    for (std::size_t i = 0; i < r.tried.size(); ++i) {
      const StableStepTry& t = r.tried[i];
      const std::string at = who + " at h = " + std::to_string(t.h);
      if (i > 0) {
        EXPECT_DOUBLE_EQ(t.h, 2 * r.tried[i - 1].h) << at;
      }
      EXPECT_EQ(t.stable, i == 0 && t.at.size() == 2 && t.last().within()) << at;
      for (const HorizonVerdict& v : t.at) {
        if (v.within()) {
          EXPECT_LE(v.energy_error, b.energy_fraction) << at;
          EXPECT_LE(v.rotation_defect, b.rotation_defect) << at;
          EXPECT_TRUE(std::isnan(v.failed_at)) << at;
        }
        // a blow-up is a failure by T, a stop one the run's status says
        if (v.blow_up != BlowUp::none) {
          EXPECT_LE(v.failed_at, t.stop_time) << at;
          EXPECT_GE(v.failed_at, 0.0) << at;
        }
        if (v.blow_up == BlowUp::stopped) {
          EXPECT_NE(t.status, Status::ok) << at;
        }
      }
    }
    if (!r.tried.front().stable) {
      EXPECT_EQ(r.tried.front().h, st.search_h_min) << who << ": the descent ends at the ladder's bottom";
    }
    // h*(T) below the blow-up step, neither rising with T (NaN: none, below every step)
    const auto rung = [](double h) { return std::isnan(h) ? -1e9 : std::log2(h); };
    for (std::size_t k = 0; k < 2; ++k) {
      const DriftLimit& d = r.drift_limited[k];
      if (!std::isnan(r.blow_up[k].h)) {
        EXPECT_LT(rung(d.h), rung(r.blow_up[k].h)) << who;
      }
      if (k > 0) {
        EXPECT_LE(rung(d.h), rung(r.drift_limited[k - 1].h)) << who;
        if (!std::isnan(r.blow_up[k - 1].h)) {
          EXPECT_LE(rung(r.blow_up[k].h), rung(r.blow_up[k - 1].h)) << who;
        }
      }
    }
  }
}

TEST(Stability, HorizonsAreReadStrictly) {
  EXPECT_EQ(parse_stability_horizons("10,100,1000", "stability-horizons"), (std::vector<double>{10.0, 100.0, 1000.0}));
  EXPECT_EQ(parse_stability_horizons("2.5", "stability-horizons"), (std::vector<double>{2.5}));
  for (const char* bad :
       {"100,10", "10,10", "0", "-5", "inf", "nan", "1e7", "", "abc", "10,,100", "10;100", "2^3..2^1"}) {
    try {
      (void)parse_stability_horizons(bad, "stability-horizons");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "stability-horizons") << bad;
    }
  }
}

TEST(Stability, TheHorizonsOptionRunsTheStudyOrExitsWithTwo) {
  const std::string out = testing::cli_temp_file("stability-horizons.json").string();
  const std::string run = "run --scenes plane --integrators rk4 --h 0.5 --tol 1e-4 --repeats 1 --out " + out;
  testing::CliOutcome o = testing::run_rollbench(run + " --stability-horizons 100,10");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'stability-horizons': the horizons must increase"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  o = testing::run_rollbench(run + " --stability-horizons 0,10");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'stability-horizons'"), std::string::npos) << o.err;
  o = testing::run_rollbench(run + " --no-stability --stability-horizons 10");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--no-stability cannot go with --stability-horizons"), std::string::npos) << o.err;
  // without a preset's study it runs the default preset's, at these horizons
  o = testing::run_rollbench(run + " --stability-horizons 2,4");
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(testing::slurp(out));
  EXPECT_EQ(j.at("options").at("stability").at("horizons"), nlohmann::json({2.0, 4.0}));
  const nlohmann::json& entries = j.at("stability").at("largest_stable_h");
  ASSERT_EQ(entries.size(), preset("default").stability.scenes.size());
  for (const nlohmann::json& e : entries) {
    ASSERT_EQ(e.at("drift_limited").size(), 2u);
    EXPECT_EQ(e.at("drift_limited")[1].at("horizon"), 4.0);
    EXPECT_EQ(e.at("blow_up").at("at").size(), 2u);
    EXPECT_TRUE(e.at("blow_up").at("same_at_every_horizon").is_boolean());
  }
}

}  // namespace
}  // namespace rb

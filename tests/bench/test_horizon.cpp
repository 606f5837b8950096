// The horizon study (bench/lib/horizon.hpp): every series is classed by
// classify_growth (bench/lib/growth_class.hpp, its own tests) with the
// study's rules; an undecided class runs the next decade while the budget
// allows, and says when the budget stopped it; the series is the envelope
// over each window (every step measured, compared; the window grid alone
// gives the same), not a running maximum; a flat RK4's rotation defect grows
// linearly where R feeds back while RKMK4's stays at rounding level (on the
// group by construction); series identical by construction are marked once,
// within a sweep and across merged shards; a failing method is a record
// without a fit; bad options are refused with their names; the report
// carries the study and merging shards keeps every run once.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench/lib/drift.hpp"
#include "bench/lib/horizon.hpp"
#include "bench/lib/presets.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;

TEST(HorizonFit, SampleStepsAreLogSpacedWholeSteps) {
  const std::vector<long> n = horizon_sample_steps(1000, 4);
  const std::vector<long> expected = {1, 2, 3, 6, 10, 18, 32, 56, 100, 178, 316, 562, 1000};
  EXPECT_EQ(n, expected);
  EXPECT_EQ(horizon_sample_steps(100000, 8).back(), 100000);
  EXPECT_DOUBLE_EQ(rounding_level(10000, 2.0), 100.0 * 2.220446049250313e-16 * 100.0 * 2.0);
}

// the study's runs alone: the price runs have tests of their own
HorizonSpec small_study(long steps) {
  HorizonSpec s = preset("default").horizon;
  s.steps = steps;
  s.coarsenings.clear();
  return s;
}

TEST(Horizon, FlatRk4DefectGrowsWhileRkmk4StaysOnTheGroup) {
  const Problem problem = make_problem(load_scene("chaplygin-bumpy-long"));
  const HorizonSpec spec = small_study(20000);
  const HorizonRecord flat = horizon_run(problem, find_integrator("rk4"), spec);
  const HorizonRecord lie = horizon_run(problem, find_integrator("rkmk4"), spec);
  for (const HorizonRecord* r : {&flat, &lie}) {
    ASSERT_EQ(r->status, Status::ok) << r->message;
    EXPECT_TRUE(r->r_feeds_back);
    EXPECT_EQ(r->cost.steps, 20000);  // no step shortened to land on a sample
    EXPECT_EQ(r->t.size(), horizon_sample_steps(20000, spec.samples_per_decade).size());
    EXPECT_DOUBLE_EQ(r->t.back(), 20000 * spec.h);
  }
  // the flat method's defect: a steady drift, far above rounding
  // (at 20000 steps its per-decade slopes still move: 1.16, 0.90, 0.99, undecided)
  EXPECT_NE(flat.defect_fit.growth_class, GrowthClass::rounding) << flat.defect_fit.reason;
  EXPECT_GT(flat.defect_fit.p, 0.8);
  EXPECT_LT(flat.defect_fit.p, 1.2);
  EXPECT_FALSE(flat.defect_fit.at_rounding);
  EXPECT_GT(flat.defect_fit.largest, 1e-6);
  // the Lie method's: rounding only
  EXPECT_TRUE(lie.defect_fit.at_rounding);
  EXPECT_EQ(lie.defect_fit.growth_class, GrowthClass::rounding);
  EXPECT_LT(lie.defect_fit.largest, 1e-12);
  // its energy error is smaller than the flat one's, whose R leaves SO(3)
  EXPECT_LT(lie.energy_error.back(), flat.energy_error.back());
}

TEST(Horizon, TheSeriesIsTheEnvelopeOverEachWindowNotARunningMaximum) {
  // every step measured (dense_outputs = steps): sample k holds the largest
  // error over the steps after sample k - 1 up to its own; the grid of
  // window_outputs states in each window, as long as the windows, alone
  // measures every step too (the uniform grid a single state)
  const Problem problem = make_problem(load_scene("chaplygin-bumpy-long"));
  HorizonSpec spec = small_study(4000);
  spec.dense_outputs = spec.steps;
  const Integrator& rk4 = find_integrator("rk4");
  const HorizonRecord r = horizon_run(problem, rk4, spec);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  HorizonSpec windows = spec;
  windows.dense_outputs = 1;
  windows.window_outputs = spec.steps;
  const HorizonRecord w = horizon_run(problem, rk4, windows);
  EXPECT_EQ(w.energy_error, r.energy_error);
  EXPECT_EQ(w.rotation_defect, r.rotation_defect);
  // the defaults: 20000 states in all, and at least 64 in each window
  EXPECT_EQ(preset("default").horizon.window_outputs, 64);
  RunOptions every;
  every.t_end = r.t_end;
  every.h = spec.h;
  for (long n = 1; n < spec.steps; ++n) every.output_times.push_back(spec.h * n);
  const RunResult run = rk4.integrate(problem, every);
  ASSERT_EQ(run.output.t.size(), static_cast<std::size_t>(spec.steps));
  const DriftMeter meter(problem);
  const std::vector<long> samples = horizon_sample_steps(spec.steps, spec.samples_per_decade);
  ASSERT_EQ(r.t.size(), samples.size());
  bool falls = false;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    double energy = 0.0, defect = 0.0;
    for (long n = k == 0 ? 1 : samples[k - 1] + 1; n <= samples[k]; ++n) {
      const Drift d = meter.at(run.output.y[n - 1]);
      energy = std::max(energy, d.energy);
      defect = std::max(defect, d.rotation_defect);
    }
    EXPECT_DOUBLE_EQ(r.energy_error[k], energy) << "sample " << k;
    EXPECT_DOUBLE_EQ(r.rotation_defect[k], defect) << "sample " << k;
    if (k > 0 && r.energy_error[k] < r.energy_error[k - 1]) falls = true;
  }
  EXPECT_TRUE(falls) << "an envelope of an oscillating error falls somewhere; a running maximum never does";
}

TEST(Horizon, EachInvariantOfTheSceneIsRecordedLikeTheEnergy) {
  // Routh's two integrals on the paraboloid: the envelope of InvariantMeter's
  // errors over each window, every step measured, and a fit of each
  const Problem problem = make_problem(load_scene("paraboloid"));
  HorizonSpec spec = small_study(4000);
  spec.dense_outputs = spec.steps;
  const Integrator& rk4 = find_integrator("rk4");
  const HorizonRecord r = horizon_run(problem, rk4, spec);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  ASSERT_EQ(r.invariants.size(), 2u);
  EXPECT_EQ(r.invariants[0].name, "routh-paraboloid.J1");
  EXPECT_EQ(r.invariants[1].name, "routh-paraboloid.J2");
  RunOptions every;
  every.t_end = r.t_end;
  every.h = spec.h;
  for (long n = 1; n < spec.steps; ++n) every.output_times.push_back(spec.h * n);
  const RunResult run = rk4.integrate(problem, every);
  const InvariantMeter meter(problem);
  const std::vector<long> samples = horizon_sample_steps(spec.steps, spec.samples_per_decade);
  for (const InvariantSeries& s : r.invariants) {
    ASSERT_EQ(s.error.size(), samples.size());
    EXPECT_TRUE(std::isfinite(s.fit.p)) << s.name << ": " << s.fit.reason;
    EXPECT_NE(s.fit.growth_class, GrowthClass::none) << s.name;
    EXPECT_FALSE(s.fit.reason.empty()) << s.name;
    EXPECT_DOUBLE_EQ(s.fit.rounding_level, rounding_level(spec.steps, 1.0));
    // rk4 at h = 1/128 misses them by far more than rounding
    EXPECT_FALSE(s.fit.at_rounding) << s.name;
  }
  for (std::size_t k = 0; k < samples.size(); ++k)
    for (std::size_t i = 0; i < 2; ++i) {
      double largest = 0.0;
      for (long n = k == 0 ? 1 : samples[k - 1] + 1; n <= samples[k]; ++n)
        largest = std::max(largest, meter.errors(run.output.y[n - 1])[i]);
      EXPECT_DOUBLE_EQ(r.invariants[i].error[k], largest) << "sample " << k;
    }
  // the report: one entry per integral beside the energy, none for a scene without
  HorizonResults results;
  results.runs = {r, horizon_run(make_problem(load_scene("bumpy-long")), rk4, small_study(1000))};
  const nlohmann::json runs = horizon_json(results)["runs"];
  const nlohmann::json& inv = runs[0].at("invariants");
  ASSERT_EQ(inv.size(), 2u);
  EXPECT_EQ(inv[1].at("name"), "routh-paraboloid.J2");
  EXPECT_EQ(inv[1].at("error").size(), runs[0].at("t").size());
  EXPECT_DOUBLE_EQ(inv[1].at("fit").at("p").get<double>(), r.invariants[1].fit.p);
  for (const char* key : {"class", "reason", "decades", "p_earlier", "ci95_earlier", "p_last", "ci95_last",
                          "at_rounding", "rounding_level"})
    EXPECT_TRUE(inv[0].at("fit").contains(key)) << key;
  EXPECT_TRUE(runs[1].at("invariants").empty());
}

TEST(Horizon, TheChaplyginIntegralsShowRLeavingTheGroup) {
  // on the plane v is kept exactly by every method; M . M = |R^T v|^2
  // moves only with R's drift: a flat rk4's grows, rkmk4's stays at rounding
  const Problem problem = make_problem(load_scene("chaplygin-plane"));
  const HorizonSpec spec = small_study(20000);
  const HorizonRecord flat = horizon_run(problem, find_integrator("rk4"), spec);
  const HorizonRecord lie = horizon_run(problem, find_integrator("rkmk4"), spec);
  ASSERT_EQ(flat.status, Status::ok) << flat.message;
  ASSERT_EQ(lie.status, Status::ok) << lie.message;
  ASSERT_EQ(flat.invariants.size(), 2u);
  EXPECT_EQ(flat.invariants[0].name, "chaplygin-plane.K.K");
  EXPECT_FALSE(flat.invariants[0].fit.at_rounding);
  EXPECT_GT(flat.invariants[0].fit.largest, 1e-8);
  EXPECT_GT(flat.invariants[0].fit.p, 0.8);
  EXPECT_TRUE(lie.invariants[0].fit.at_rounding) << lie.invariants[0].fit.largest;
  EXPECT_TRUE(lie.invariants[1].fit.at_rounding) << lie.invariants[1].fit.largest;
  // both kinematic (docs/model.md, "Which integrals show structure"), and so
  // recorded; the energy at the nearest rotation beside the flat one: rk4's
  // flat H hides R's drift, rkmk4's two agree
  for (const InvariantSeries& s : flat.invariants) EXPECT_EQ(s.kind, IntegralKind::kinematic) << s.name;
  ASSERT_EQ(flat.energy_error_on_group.size(), flat.energy_error.size());
  EXPECT_GT(flat.energy_on_group_fit.largest, 100.0 * flat.energy_fit.largest);
  for (std::size_t k = 0; k < lie.energy_error.size(); ++k)
    EXPECT_NEAR(lie.energy_error_on_group[k], lie.energy_error[k], 1e-14) << "sample " << k;
  HorizonResults results;
  results.runs = {flat, lie};
  const nlohmann::json runs = horizon_json(results)["runs"];
  EXPECT_EQ(runs[0].at("invariants")[0].at("kind"), "kinematic");
  EXPECT_EQ(runs[0].at("energy_error_on_group").size(), runs[0].at("t").size());
  EXPECT_DOUBLE_EQ(runs[0].at("fit").at("energy_error_on_group").at("largest").get<double>(),
                   flat.energy_on_group_fit.largest);
  EXPECT_TRUE(runs[0].at("same_as").contains("energy_error_on_group"));
  EXPECT_TRUE(runs[0].at("rhs_equivalents").is_number());
}

TEST(Horizon, EachSeriesIsClassedWithTheStudysRules) {
  // the record's fits are classify_growth of its series with the spec's
  // window and spread, and the report carries each class, its reason and
  // its per-decade slopes
  const Problem problem = make_problem(load_scene("bumpy-long"));
  HorizonSpec spec = small_study(20000);
  const HorizonRecord r = horizon_run(problem, find_integrator("rkmk4"), spec);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  GrowthRules rules;
  rules.decades = spec.fit_decades;
  rules.spread = spec.asymptotic_spread;
  const GrowthFit energy = classify_growth(r.t, r.energy_error, rounding_level(spec.steps, r.energy_scale), rules);
  EXPECT_EQ(r.energy_fit.growth_class, energy.growth_class);
  EXPECT_EQ(r.energy_fit.reason, energy.reason);
  EXPECT_DOUBLE_EQ(r.energy_fit.t_from, r.t_end / 1000.0);  // three decades
  ASSERT_EQ(r.energy_fit.decades.size(), 4u);               // 20000 steps: 4 whole decades of t
  HorizonResults results;
  results.runs = {r};
  const nlohmann::json fit = horizon_json(results)["runs"][0].at("fit").at("energy_error");
  EXPECT_EQ(fit.at("class").is_null(), energy.growth_class == GrowthClass::none);
  EXPECT_EQ(fit.at("reason"), energy.reason);
  ASSERT_EQ(fit.at("decades").size(), 4u);
  EXPECT_DOUBLE_EQ(fit.at("decades")[3].at("p").get<double>(), energy.decades[3].p);
  EXPECT_DOUBLE_EQ(fit.at("decades")[3].at("t_to").get<double>(), r.t_end);
  // a spread no slope set can pass: nothing above rounding is decided
  spec.asymptotic_spread = -1.0;
  const HorizonRecord strict = horizon_run(problem, find_integrator("rkmk4"), spec);
  EXPECT_EQ(strict.energy_fit.growth_class, GrowthClass::undecided);
  EXPECT_NE(strict.energy_fit.reason.find("drift"), std::string::npos) << strict.energy_fit.reason;
}

TEST(Horizon, SeriesTheSameByConstructionAreMarkedOnce) {
  // a homogeneous ball: rk4, rkmk4, cf4 and rk4-projected step (v, alpha)
  // with one tableau, and R does not feed back; euler differs
  HorizonSpec spec = small_study(20000);
  spec.integrators = {"rk4", "rkmk4", "cf4", "rk4-projected", "rk38", "euler"};
  spec.scenes = {"bumpy-long", "chaplygin-bumpy-long"};
  SweepSpec sweep;
  sweep.horizon = spec;
  const nlohmann::json runs = horizon_json(run_horizon(sweep, [](const std::string&) {}))["runs"];
  ASSERT_EQ(runs.size(), 12u);
  for (const nlohmann::json& r : runs) {
    const std::string name = r["integrator"], scene = r["scene"];
    const nlohmann::json& same = r["same_as"]["energy_error"];
    if (scene == "bumpy-long" && (name == "rkmk4" || name == "cf4" || name == "rk4-projected")) {
      EXPECT_EQ(same, "rk4") << name;  // the first of them, once
    } else {
      EXPECT_TRUE(same.is_null()) << name << " on " << scene << ": " << same;
    }
    // rk4's R drifts, the others' stays at rounding: never "the same" at rounding
    EXPECT_TRUE(r["same_as"]["rotation_defect"].is_null()) << name << " on " << scene;
  }
  // a homogeneous ball's first integrals depend on (v, alpha) alone: on the
  // paraboloid the same four are twins in Routh's J1 and J2 as well
  spec.scenes = {"paraboloid"};
  sweep.horizon = spec;
  const nlohmann::json para = horizon_json(run_horizon(sweep, [](const std::string&) {}))["runs"];
  ASSERT_EQ(para.size(), 6u);
  for (const nlohmann::json& r : para) {
    const std::string name = r["integrator"];
    const nlohmann::json& same = r["same_as"]["invariants"];
    ASSERT_EQ(same.size(), 2u) << name;
    for (const char* integral : {"routh-paraboloid.J1", "routh-paraboloid.J2"}) {
      if (name == "rkmk4" || name == "cf4" || name == "rk4-projected")
        EXPECT_EQ(same[integral], "rk4") << name << " " << integral;
      else EXPECT_TRUE(same[integral].is_null()) << name << " " << integral << ": " << same[integral];
    }
  }
  EXPECT_TRUE(runs[0]["same_as"]["invariants"].empty());  // bumpy-long declares none
  // a series moved by more than its rounding level is another series
  nlohmann::json pair = nlohmann::json::array({runs[0], runs[1]});
  pair[1]["energy_error"][pair[1]["energy_error"].size() - 1] =
      pair[1]["energy_error"].back().get<double>() + 2 * pair[1]["fit"]["energy_error"]["rounding_level"].get<double>();
  mark_same_series(pair);
  EXPECT_TRUE(pair[1]["same_as"]["energy_error"].is_null());
  pair[1]["energy_error"] = pair[0]["energy_error"];
  pair[1]["scene"] = "another";
  mark_same_series(pair);
  EXPECT_TRUE(pair[1]["same_as"]["energy_error"].is_null()) << "another scene's series is not compared";
}

TEST(Horizon, AFailingMethodIsARecordWithoutAFit) {
  const Problem problem = make_problem(load_scene("bumpy-long"));
  const HorizonRecord r = horizon_run(problem, find_integrator("euler"), small_study(100000));
  EXPECT_NE(r.status, Status::ok);
  EXPECT_LT(r.stop_time, r.t_end);
  ASSERT_FALSE(r.t.empty());
  EXPECT_LE(r.t.back(), r.stop_time);
  EXPECT_TRUE(std::isnan(r.energy_fit.p));
  EXPECT_EQ(r.energy_fit.growth_class, GrowthClass::none);
  EXPECT_EQ(r.defect_fit.reason.rfind("the run stopped at t = ", 0), 0u) << r.defect_fit.reason;
  // a stopped run is not run again for a further decade
  HorizonSpec more = small_study(100000);
  more.steps_max = 1'000'000;
  const HorizonRecord d = horizon_decades(problem, find_integrator("euler"), more);
  EXPECT_NE(d.status, Status::ok);
  EXPECT_EQ(d.steps, 100000);
  EXPECT_TRUE(d.earlier.empty());
  EXPECT_TRUE(d.budget_reason.empty());
}

TEST(Horizon, BadOptionsAreRefusedWithTheirNames) {
  EXPECT_EQ(parse_horizon_steps("1e5"), 100000);
  EXPECT_EQ(parse_horizon_steps("250000"), 250000);
  EXPECT_EQ(parse_horizon_steps("12.5e3"), 12500);  // a whole number, however written
  for (const char* bad : {"12.5", "1.5e3x", "abc", "100", "2e8", "", "1e5x", " 1e5", "+1e5", "0x3E8", "-1e5"}) {
    try {
      parse_horizon_steps(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "horizon-steps");
      EXPECT_EQ(e.message(), "expected a whole number of steps from 1000 to 1e8 (e.g. 100000 or 1e6), got '" +
                                 std::string(bad) + "'");
    }
  }
  // the budget's options
  EXPECT_EQ(parse_horizon_steps("1e7", "horizon-steps-max"), 10'000'000);
  try {
    parse_horizon_steps("1e9", "horizon-steps-max");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "horizon-steps-max");
  }
  EXPECT_EQ(parse_horizon_cpu_max("600"), 600.0);
  EXPECT_EQ(parse_horizon_cpu_max("2.5"), 2.5);
  EXPECT_EQ(parse_horizon_cpu_max("1e-9"), 1e-9);
  for (const char* bad : {"0", "-1", "inf", "nan", "", "10s", "1e400", " 5", "+5", "0x10"}) {
    try {
      parse_horizon_cpu_max(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "horizon-cpu-max");
      EXPECT_EQ(e.message(), "expected seconds, a finite number > 0 (e.g. 600), got '" + std::string(bad) + "'");
    }
  }
  HorizonSpec s = small_study(10000);
  s.steps_max = 5000;  // below the steps
  try {
    check_horizon(s);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "'horizon-steps-max': expected the most steps from --horizon-steps (10000) to 100000000, got 5000");
  }
  s.steps_max = 0;
  s.cpu_max_s = 0.0;
  EXPECT_THROW(check_horizon(s), InputError);
  s.cpu_max_s = 1.0;
  s.fit_decades = 2;  // a class needs three
  EXPECT_THROW(check_horizon(s), InputError);
  s = small_study(1000);
  s.integrators = {"rk4", "rkmk-dp54-adaptive"};
  try {
    check_horizon(s);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "'horizon-integrators': 'rkmk-dp54-adaptive' is adaptive: the horizon study takes "
                 "fixed steps");
  }
  s = small_study(999);
  EXPECT_THROW(check_horizon(s), InputError);
  s = small_study(1000);
  s.scenes = {"no-such-scene"};
  EXPECT_THROW(check_horizon(s), InputError);
  s.enabled = false;  // a study that does not run is not checked
  EXPECT_NO_THROW(check_horizon(s));
}

using testing::run_rollbench;
using testing::slurp;

TEST(HorizonCli, OptionsRunTheStudyIntoTheReportAndShardsMerge) {
  const fs::path a = testing::cli_temp_file("horizon-a.json"), b = testing::cli_temp_file("horizon-b.json"),
                 merged = testing::cli_temp_file("horizon-merged.json");
  const std::string common =
      "run --scenes plane --integrators rk4 --h 0.25 --repeats 0 --horizon-steps 2000 "
      "--horizon-scenes plane --horizon-integrators rk4,rkmk4,cf4 ";
  testing::CliOutcome o = run_rollbench(common + "--shard 0/2 --out " + a.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("horizon: rk4 on plane: ok"), std::string::npos) << o.err;
  o = run_rollbench(common + "--shard 1/2 --out " + b.string());
  ASSERT_EQ(o.code, 0) << o.err;
  o = run_rollbench("merge " + a.string() + " " + b.string() + " --out " + merged.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(merged));
  EXPECT_EQ(j.at("options").at("horizon").at("steps"), 2000);
  const nlohmann::json& runs = j.at("horizon").at("runs");
  // the study's three runs, then the price runs at 4 h and 16 h (both divide 2000)
  EXPECT_EQ(j.at("options").at("horizon").at("coarsenings"), nlohmann::json::array({4, 16}));
  ASSERT_EQ(runs.size(), 9u);
  const char* names[] = {"rk4", "rkmk4", "cf4"};
  const long coarsening[] = {1, 4, 16};
  for (std::size_t i = 0; i < 9; ++i) {
    const long k = coarsening[i / 3];
    EXPECT_EQ(runs[i].at("index"), i);
    EXPECT_EQ(runs[i].at("integrator"), names[i % 3]);
    EXPECT_EQ(runs[i].at("coarsening"), k);
    EXPECT_EQ(runs[i].at("steps"), 2000 / k);
    EXPECT_DOUBLE_EQ(runs[i].at("h").get<double>(), k / 128.0);
    EXPECT_DOUBLE_EQ(runs[i].at("t_end").get<double>(), 2000 / 128.0) << "one horizon for every run";
    EXPECT_EQ(runs[i].at("t").size(), runs[i].at("rotation_defect").size());
    EXPECT_TRUE(runs[i].at("fit").at("rotation_defect").contains("p"));
  }
}

// A price run is the study's run at k h over the same horizon: only the k
// that divide the steps are run, and the run is that of a study of steps / k
// steps of k h.
TEST(Horizon, PriceRunsCoverTheSameHorizonAtCoarserSteps) {
  HorizonSpec spec = preset("default").horizon;
  spec.steps = 1000;  // 16 does not divide it
  EXPECT_EQ(price_coarsenings(spec), std::vector<long>({4}));
  spec.coarsenings = {4, 1, 4, 0, -2, 8};
  EXPECT_EQ(price_coarsenings(spec), std::vector<long>({4, 8}));
  spec.coarsenings = {8};
  spec.scenes = {"paraboloid"};
  spec.integrators = {"rk4"};
  SweepSpec sweep;
  sweep.horizon = spec;
  const HorizonResults results = run_horizon(sweep, [](const std::string&) {});
  ASSERT_EQ(results.runs.size(), 2u);
  const HorizonRecord& price = results.runs[1];
  EXPECT_EQ(price.coarsening, 8);
  EXPECT_EQ(price.steps, 125);
  EXPECT_EQ(price.cost.steps, 125);
  EXPECT_DOUBLE_EQ(price.t_end, results.runs[0].t_end);
  HorizonSpec alone = spec;
  alone.h = 8 * spec.h;
  alone.steps = 125;
  const HorizonRecord direct = horizon_run(make_problem(load_scene("paraboloid")), find_integrator("rk4"), alone);
  EXPECT_EQ(price.energy_error, direct.energy_error);
  // a coarser rk4 step, a larger energy error over the same horizon
  EXPECT_GT(price.energy_error.back(), results.runs[0].energy_error.back());
}

// The runs share --jobs threads: every record, its index and its place in
// the report are those of one thread's run, but for the timings; an
// implicit method's Newton counts are recorded, an explicit one's are 0.
TEST(HorizonCli, ThreadsGiveTheRecordsOfOneThread) {
  const fs::path one = testing::cli_temp_file("horizon-jobs1.json"), two = testing::cli_temp_file("horizon-jobs2.json");
  const std::string common =
      "run --scenes plane --integrators rk4 --h 0.25 --repeats 0 --horizon-steps 2000 "
      "--horizon-scenes plane,paraboloid-chaplygin --horizon-integrators rk4,gauss2,rkmk4 ";
  testing::CliOutcome o = run_rollbench(common + "--jobs 1 --out " + one.string());
  ASSERT_EQ(o.code, 0) << o.err;
  o = run_rollbench(common + "--jobs 2 --out " + two.string());
  ASSERT_EQ(o.code, 0) << o.err;
  nlohmann::json a = nlohmann::json::parse(slurp(one)).at("horizon").at("runs");
  nlohmann::json b = nlohmann::json::parse(slurp(two)).at("horizon").at("runs");
  ASSERT_EQ(a.size(), 18u);  // the study's 6 runs and the price runs at 4 h and 16 h
  ASSERT_EQ(b.size(), 18u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].at("index"), i);
    EXPECT_GE(b[i].at("cpu_s").get<double>(), 0.0);
    const bool implicit = a[i].at("integrator") == "gauss2";
    EXPECT_EQ(a[i].at("newton_iterations").get<long>() > 0, implicit) << a[i].at("integrator");
    EXPECT_EQ(a[i].at("jacobian_evals").get<long>() > 0, implicit) << a[i].at("integrator");
    for (nlohmann::json* run : {&a[i], &b[i]}) run->erase("wall_s"), run->erase("cpu_s");
    EXPECT_EQ(a[i], b[i]) << "run " << i;
  }
}

TEST(HorizonCli, AMergeFindsTwinSeriesAcrossShards) {
  const fs::path a = testing::cli_temp_file("twins-a.json"), b = testing::cli_temp_file("twins-b.json"),
                 merged = testing::cli_temp_file("twins-merged.json");
  const std::string common =
      "run --scenes plane --integrators rk4 --h 0.25 --repeats 0 --horizon-steps 4000 "
      "--horizon-scenes bumpy-long --horizon-integrators rk4,rkmk4 ";
  ASSERT_EQ(run_rollbench(common + "--shard 0/2 --out " + a.string()).code, 0);
  ASSERT_EQ(run_rollbench(common + "--shard 1/2 --out " + b.string()).code, 0);
  // each shard alone holds one of the two: no twin
  const nlohmann::json shard = nlohmann::json::parse(slurp(b));
  ASSERT_EQ(shard.at("horizon").at("runs").size(), 3u);
  EXPECT_TRUE(shard.at("horizon").at("runs")[0].at("same_as").at("energy_error").is_null());
  ASSERT_EQ(run_rollbench("merge " + a.string() + " " + b.string() + " --out " + merged.string()).code, 0);
  const nlohmann::json whole = nlohmann::json::parse(slurp(merged));
  const nlohmann::json& runs = whole.at("horizon").at("runs");
  // rk4, rkmk4 at h, then at 4 h and 16 h: twins within a step, never across
  ASSERT_EQ(runs.size(), 6u);
  for (std::size_t i = 0; i < 6; i += 2) {
    EXPECT_TRUE(runs[i].at("same_as").at("energy_error").is_null()) << i;
    EXPECT_EQ(runs[i + 1].at("same_as").at("energy_error"), "rk4") << i + 1;
  }
}

TEST(HorizonCli, BadOptionsExitWithTwo) {
  const std::string out = " --out " + testing::cli_temp_file("horizon-bad.json").string();
  const std::string base = "run --scenes plane --integrators rk4 --h 0.25 --repeats 0 ";
  testing::CliOutcome o = run_rollbench(base + "--horizon-steps 12.5" + out);
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'horizon-steps': expected a whole number of steps from 1000 to 1e8 (e.g. 100000 or "
            "1e6), got '12.5'\n");
  o = run_rollbench(base + "--horizon-steps 1e4 --horizon-integrators rk4,gsl-rkf45-adaptive" + out);
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'horizon-integrators': 'gsl-rkf45-adaptive' is adaptive: the horizon study takes "
            "fixed steps\n");
  o = run_rollbench(base + "--no-horizon --horizon-steps 1e4" + out);
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'no-horizon'"), std::string::npos) << o.err;
  // without a preset or an option: no study, an empty section
  const fs::path plain = testing::cli_temp_file("horizon-none.json");
  o = run_rollbench(base + "--out " + plain.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(plain));
  EXPECT_EQ(j.at("options").at("horizon").at("enabled"), false);
  EXPECT_TRUE(j.at("horizon").at("runs").empty());
  EXPECT_TRUE(preset("default").horizon.enabled);
  EXPECT_EQ(preset("default").horizon.steps, 1'000'000);
  EXPECT_EQ(preset("full").horizon.steps, 10'000'000);
  // no further decade unless asked for (issue 55: the default preset's cost)
  EXPECT_EQ(preset("default").horizon.steps_max, 0);
  EXPECT_EQ(preset("full").horizon.steps_max, 0);
  EXPECT_EQ(preset("default").horizon.cpu_max_s, 600.0);
  o = run_rollbench(base + "--horizon-steps 1e4 --horizon-steps-max 1e3" + out);
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'horizon-steps-max': expected the most steps from --horizon-steps (10000) to 100000000, got "
            "1000\n");
  o = run_rollbench(base + "--horizon-cpu-max 0" + out);
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 'horizon-cpu-max': expected seconds, a finite number > 0 (e.g. 600), got '0'\n");
}

// The study runs decade by decade: a run whose class is undecided runs
// again at 10 times the steps while the budget allows, the record is the
// last run with the earlier ones listed, and the report says when the
// budget stopped an undecided class. rk4 on the bumpy bowl is undecided at
// 10^3 steps (its first decade of steps is the window's); on the plane its
// energy is at rounding and its defect linear at once.
TEST(HorizonCli, UndecidedRunsGoOnDecadeByDecadeWithinTheBudget) {
  const fs::path file = testing::cli_temp_file("horizon-decades.json");
  const std::string common =
      "run --scenes plane --integrators rk4 --h 0.25 --repeats 0 --horizon-steps 1000 --horizon-scenes "
      "bumpy-long,plane --horizon-integrators rk4 --out " +
      file.string();
  testing::CliOutcome o = run_rollbench(common + " --horizon-steps-max 1e5");
  ASSERT_EQ(o.code, 0) << o.err;
  nlohmann::json j = nlohmann::json::parse(slurp(file));
  EXPECT_EQ(j.at("options").at("horizon").at("steps_max"), 100000);
  nlohmann::json runs = j.at("horizon").at("runs");
  ASSERT_EQ(runs.size(), 4u);  // two study runs, two price runs at 4 h (16 does not divide 1000)
  const nlohmann::json& bowl = runs[0];
  ASSERT_EQ(bowl.at("scene"), "bumpy-long");
  EXPECT_EQ(bowl.at("study_steps"), 1000);
  const nlohmann::json& earlier = bowl.at("earlier_runs");
  ASSERT_FALSE(earlier.empty()) << "rk4 on bumpy-long is undecided at 1000 steps";
  long steps = 1000;
  for (const nlohmann::json& e : earlier) {
    EXPECT_EQ(e.at("steps"), steps);
    EXPECT_EQ(e.at("status"), "ok");
    EXPECT_DOUBLE_EQ(e.at("t_end").get<double>(), steps / 128.0);
    EXPECT_TRUE(e.at("largest").at("energy_error").is_number());
    const nlohmann::json& c = e.at("class");
    EXPECT_TRUE(c.at("energy_error") == "undecided" || c.at("energy_error_on_group") == "undecided" ||
                c.at("rotation_defect") == "undecided")
        << c;
    steps *= 10;
  }
  EXPECT_EQ(bowl.at("steps_planned"), steps);
  EXPECT_LE(steps, 100000);
  EXPECT_DOUBLE_EQ(bowl.at("t_end").get<double>(), steps / 128.0);
  bool undecided = false;
  for (const char* key : {"energy_error", "energy_error_on_group", "rotation_defect"})
    undecided = undecided || bowl.at("fit").at(key).at("class") == "undecided";
  EXPECT_EQ(bowl.at("budget_ran_out"), undecided);
  if (undecided) {
    EXPECT_EQ(steps, 100000);
    EXPECT_EQ(bowl.at("budget_reason"),
              "the next decade, 1000000 steps, is past the study's most, 100000 (--horizon-steps-max)");
  }
  EXPECT_NE(o.err.find("horizon: rk4 on bumpy-long: ok (1000 steps undecided, "), std::string::npos) << o.err;
  // decided at once: one run
  const nlohmann::json& plane = runs[1];
  EXPECT_EQ(plane.at("fit").at("energy_error_on_group").at("class"), "rounding");
  EXPECT_EQ(plane.at("fit").at("rotation_defect").at("class"), "linear");
  EXPECT_TRUE(plane.at("earlier_runs").empty());
  EXPECT_EQ(plane.at("steps_planned"), 1000);
  EXPECT_EQ(plane.at("budget_ran_out"), false);
  EXPECT_TRUE(plane.at("budget_reason").is_null());
  // a price run is never run again: one run of steps / k
  EXPECT_EQ(runs[2].at("coarsening"), 4);
  EXPECT_EQ(runs[2].at("steps_planned"), 250);
  EXPECT_EQ(runs[2].at("study_steps"), 250);
  EXPECT_TRUE(runs[2].at("earlier_runs").empty());

  // a CPU budget no decade fits: the first run only, and why
  o = run_rollbench(common + " --horizon-steps-max 1e5 --horizon-cpu-max 1e-9");
  ASSERT_EQ(o.code, 0) << o.err;
  runs = nlohmann::json::parse(slurp(file)).at("horizon").at("runs");
  EXPECT_TRUE(runs[0].at("earlier_runs").empty());
  EXPECT_EQ(runs[0].at("steps_planned"), 1000);
  EXPECT_EQ(runs[0].at("budget_ran_out"), true);
  const std::string why = runs[0].at("budget_reason");
  EXPECT_EQ(why.rfind("the next decade, 10000 steps, would take about ", 0), 0u) << why;
  EXPECT_NE(why.find("s of CPU (10 times this run's), past 1e-09 s (--horizon-cpu-max)"), std::string::npos) << why;
  // without --horizon-steps-max: no further decade, and the report says so
  o = run_rollbench(common);
  ASSERT_EQ(o.code, 0) << o.err;
  runs = nlohmann::json::parse(slurp(file)).at("horizon").at("runs");
  EXPECT_EQ(runs[0].at("steps_planned"), 1000);
  EXPECT_EQ(runs[0].at("budget_reason"),
            "the next decade, 10000 steps, is past the study's most, 1000 (--horizon-steps-max)");
}

}  // namespace
}  // namespace rb

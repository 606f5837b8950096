// The runner's report: the quick preset's report against the schema, its
// observed orders, its references, failures as data, and sharding.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "bench/lib/report.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

using json = nlohmann::json;

SweepSpec quick_once() {
  SweepSpec spec = preset("quick");
  spec.repeats = 1;  // timings are not what these tests check
  return spec;
}

Report run_typed_report(const SweepSpec& spec) {
  const auto quiet = [](const std::string&) {};
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  const std::vector<RunRecord> runs = run_sweep(spec, scenes, quiet);
  return make_report(spec, scenes, runs, run_stability(spec, quiet));
}

json run_report(const SweepSpec& spec) { return to_json(run_typed_report(spec)); }

const Report& quick_typed_report() {
  static const Report report = run_typed_report(quick_once());
  return report;
}

const json& quick_report() {
  static const json report = to_json(quick_typed_report());
  return report;
}

void expect_keys(const json& j, std::initializer_list<std::pair<const char*, json::value_t>> keys,
                 const std::string& where) {
  for (const auto& [key, type] : keys) {
    ASSERT_TRUE(j.contains(key)) << where << " lacks '" << key << "'";
    if (type == json::value_t::number_float) {
      EXPECT_TRUE(j[key].is_number() || j[key].is_null()) << where << "." << key;
    } else {
      EXPECT_EQ(j[key].type(), type) << where << "." << key;
    }
  }
}

TEST(Report, QuickPresetFollowsTheSchemaAndRoundTrips) {
  const json& r = quick_report();
  using t = json::value_t;
  expect_keys(r,
              {{"schema", t::string},
               {"created", t::string},
               {"git", t::string},
               {"machine", t::object},
               {"build", t::object},
               {"runs", t::array},
               {"orders", t::array},
               {"references", t::array},
               {"stability", t::object},
               {"tolerance_fits", t::array},
               {"timed_call", t::object}},
              "report");
  EXPECT_EQ(r["schema"], "rollbench.report/2");
  expect_keys(r["machine"], {{"cpu", t::string}, {"cores", t::number_unsigned}, {"os", t::string}}, "machine");
  expect_keys(r["build"], {{"compiler", t::string}, {"flags", t::string}, {"type", t::string}}, "build");
  ASSERT_FALSE(r["runs"].empty());
  for (const json& run : r["runs"]) {
    expect_keys(run,
                {{"scene", t::string},
                 {"integrator", t::string},
                 {"family", t::string},
                 {"declared_order", t::number_integer},
                 {"adaptive", t::boolean},
                 {"h", t::number_float},
                 {"rtol", t::number_float},
                 {"atol", t::number_float},
                 {"status", t::string},
                 {"stop_time", t::number_float},
                 {"steps", t::number_integer},
                 {"rejected", t::number_integer},
                 {"rhs_evals", t::number_integer},
                 {"wall_s", t::object},
                 {"error", t::object},
                 {"drift", t::object},
                 {"final", t::object},
                 {"error_max", t::object},
                 {"timed_outputs", t::number_unsigned}},
                "run");
    expect_keys(
        run["wall_s"],
        {{"median", t::number_float}, {"min", t::number_float}, {"max", t::number_float}, {"samples", t::array}},
        "wall_s");
    for (const char* errors : {"error", "error_max"})
      expect_keys(run[errors],
                  {{"reference", t::string},
                   {"contact", t::number_float},
                   {"centre", t::number_float},
                   {"omega", t::number_float},
                   {"rotation", t::number_float},
                   {"worst", t::number_float}},
                  errors);
    EXPECT_EQ(run["timed_outputs"], 1u) << "the quick preset times the run to t_end alone";
    EXPECT_EQ(run["adaptive"].get<bool>(), run["h"].is_null());
  }
  const json again = json::parse(r.dump());
  EXPECT_EQ(again, r);
}

// The components are listed once (bench/lib/error_components.hpp) and the
// report carries the list: every run's errors and every order hold exactly
// those, and the fits read from the written runs are the report's own.
TEST(Report, TheReportListsItsErrorComponentsAndItsFitsReadThemBack) {
  const json again = json::parse(quick_report().dump());
  const json expected = json::parse(R"([
    {"name": "contact", "label": "contact-point error", "unit": "m", "scale": "radius"},
    {"name": "centre", "label": "centre error", "unit": "m", "scale": "radius"},
    {"name": "omega", "label": "angular-velocity error", "unit": "rad/s", "scale": "omega_scale"},
    {"name": "rotation", "label": "rotation error", "unit": "rad", "scale": "1"}])");
  ASSERT_EQ(again.at("error_components"), expected);
  for (const json& run : again["runs"])
    for (const json& c : expected) EXPECT_TRUE(run["error"].contains(c["name"])) << c["name"];
  ASSERT_FALSE(again["orders"].empty());
  for (const json& o : again["orders"]) {
    EXPECT_EQ(o["observed"].size(), expected.size());
    for (const json& c : expected) EXPECT_TRUE(o["verdict"].contains(c["name"])) << c["name"];
  }
  ReferenceFloors floors;
  for (const json& ref : again["references"]) floors[ref["scene"]] = order_scale_of(ref);
  const std::vector<FitRun> runs = fit_runs_of(again["runs"], "quick.json");
  EXPECT_EQ(orders_json(fit_orders(runs, floors)), again["orders"]);
  EXPECT_EQ(tolerance_fits_json(fit_tolerances(runs)), again["tolerance_fits"]);
}

// A report read back (what merge and score --peers read) writes the JSON it
// was read from, and its summary table is the sweep's own.
TEST(Report, AReportReadBackWritesItselfAndTheSameSummary) {
  const json written = json::parse(quick_report().dump());
  const Report again = report_from_json(written, "quick.json");
  EXPECT_EQ(json::parse(to_json(again).dump()), written);
  ASSERT_EQ(again.runs.size(), quick_typed_report().runs.size());
  ASSERT_EQ(again.orders.size(), quick_typed_report().orders.size());
  const std::string table = summary_table(quick_typed_report());
  EXPECT_EQ(summary_table(again), table);
  // a row per (scene, integrator), its order the contact point's observed slope
  std::vector<std::pair<std::string, std::string>> keys;
  for (const json& run : written["runs"]) {
    const std::pair<std::string, std::string> key{run["scene"], run["integrator"]};
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  EXPECT_EQ(static_cast<std::size_t>(std::count(table.begin(), table.end(), '\n')), keys.size() + 2);
  for (const json& o : written["orders"]) {
    if (!o["observed"]["contact"].is_number()) continue;
    char order[32];
    std::snprintf(order, sizeof order, "%.2f", o["observed"]["contact"].get<double>());
    char start[128];
    std::snprintf(start, sizeof start, "%-16s %-28s %9s", o["scene"].get<std::string>().c_str(),
                  o["integrator"].get<std::string>().c_str(), order);
    EXPECT_NE(table.find(start), std::string::npos) << start;
  }
}

double observed(const json& report, const std::string& scene, const std::string& integrator, const char* component) {
  for (const json& o : report["orders"])
    if (o["scene"] == scene && o["integrator"] == integrator)
      return o["observed"][component].is_number() ? o["observed"][component].get<double>() : -1.0;
  return -1.0;
}

// The timed call's validity checks are part of its work: every evaluation
// a step makes is checked (docs/design.md), so a run's checks are its rhs
// evaluations plus the start and the end, less the two of an adaptive
// method's starting-step guess where it makes one, and for an adaptive
// method the evaluations on the paths of its steps that moved the contact
// point more than r/8 (docs/design.md, "Validity along every step"); a
// fixed-step method's checks per step are its evaluations per step.
TEST(Report, TimedRunsCountTheirValidityChecksAsTheirEvaluations) {
  int fixed = 0;
  for (const json& run : quick_report()["runs"]) {
    ASSERT_TRUE(run.contains("validity_checks")) << run["integrator"];
    if (run["status"] != "ok") continue;
    const long checks = run["validity_checks"].get<long>(), evals = run["rhs_evals"].get<long>();
    if (run["adaptive"].get<bool>()) {
      EXPECT_GE(checks, evals) << run["scene"] << " " << run["integrator"];
    } else {
      EXPECT_EQ(checks, evals + 2) << run["scene"] << " " << run["integrator"];
      ++fixed;
    }
  }
  EXPECT_GT(fixed, 10);
}

TEST(Report, ObservedOrdersOfTheQuickPreset) {
  const json& r = quick_report();
  struct Expect {
    const char* method;
    const char* component;
    double order;
  };
  for (const Expect e :
       {Expect{"euler", "contact", 1}, Expect{"exp-euler", "contact", 1}, Expect{"rk4", "contact", 4},
        Expect{"rkmk4", "contact", 4}, Expect{"rkmk4", "rotation", 4}, Expect{"rkmk4-seminar", "rotation", 3},
        Expect{"odeint-rk4", "contact", 4}, Expect{"gsl-rk4", "contact", 4}})
    EXPECT_NEAR(observed(r, "valley-sideways", e.method, e.component), e.order, 0.2) << e.method << " " << e.component;
  // every verdict is one of three, and a clean fourth-order method's are as declared
  for (const json& o : r["orders"])
    for (const auto& [component, verdict] : o["verdict"].items())
      EXPECT_TRUE(verdict == "as declared" || verdict == "lower" || verdict == "inconclusive") << verdict;
  for (const json& o : r["orders"])
    if (o["scene"] == "valley-sideways" && (o["integrator"] == "rkmk4" || o["integrator"] == "rkmk4-seminar")) {
      EXPECT_EQ(o["verdict"]["rotation"], "as declared") << o["integrator"] << ": " << o["ci95"].dump();
      EXPECT_EQ(o["pass"], true) << o["integrator"];
    }
}

TEST(Report, ReferencesAgreeWithTheirCrossCheck) {
  const json& r = quick_report();
  ASSERT_EQ(r["references"].size(), 3u);
  for (const json& ref : r["references"]) {
    EXPECT_LT(ref["error"].get<double>(), 1e-10) << ref["scene"];
    if (ref["scene"] == "bowl-planar") {
      EXPECT_EQ(ref["kind"], "exact");
    }
  }
}

// Each run carries the energy error at the nearest rotation beside the flat
// one (docs/model.md, "How the energy error is measured") and its cost in
// rhs-equivalents, an implicit method's Jacobians and Newton passes
// included (docs/formats.md, "A run").
TEST(Report, RunsCarryTheEnergyAtTheNearestRotationAndTheirCostInRhsEquivalents) {
  SweepSpec spec = quick_once();
  spec.scenes = {"chaplygin-plane"};
  spec.integrators = {"rk4", "rkmk4", "dg2", "dla2"};
  spec.hs = {1.0 / 64};
  spec.tols.clear();
  spec.extend_ladders = false;
  spec.stability.enabled = false;
  spec.horizon.enabled = false;
  const json r = run_report(spec);
  std::map<std::string, json> by;
  for (const json& run : r["runs"]) by[run["integrator"]] = run;
  ASSERT_EQ(by.size(), 4u);
  for (const auto& [name, run] : by) {
    SCOPED_TRACE(name);
    ASSERT_EQ(run["status"], "ok") << run["message"];
    ASSERT_TRUE(run["drift"]["energy_on_group"].is_number());
    ASSERT_TRUE(run["rhs_equivalents"].is_number());
  }
  const auto drift = [&](const char* name, const char* key) { return by[name]["drift"][key].get<double>(); };
  // dg2 keeps the flat H; the real ball's (R drifts off SO(3)) moves; rk4's
  // flat one hides most of its error; a Lie method's two agree
  EXPECT_LT(drift("dg2", "energy"), 1e-13);
  EXPECT_GT(drift("dg2", "energy_on_group"), 1e-8);
  EXPECT_GT(drift("rk4", "energy_on_group"), 100.0 * drift("rk4", "energy"));
  EXPECT_NEAR(drift("rkmk4", "energy_on_group"), drift("rkmk4", "energy"), 1e-13);
  // an explicit method's cost is its evaluations; dla2's is far above its 1 rhs a step
  EXPECT_EQ(by["rk4"]["rhs_equivalents"].get<double>(), by["rk4"]["rhs_evals"].get<double>());
  EXPECT_TRUE(by["rk4"]["implicit_cost"].is_null());
  const json& dla2 = by["dla2"];
  const double steps = dla2["steps"].get<double>();
  EXPECT_EQ(dla2["rhs_evals"].get<double>(), steps);
  EXPECT_GT(dla2["rhs_equivalents"].get<double>(), 6.0 * steps);
  const json& parts = dla2["implicit_cost"];
  EXPECT_EQ(parts["jacobian_columns"].get<double>(), 5.0 * steps);
  EXPECT_EQ(parts["lu_decompositions"].get<double>(), steps);
  EXPECT_EQ(parts["flops_per_rhs"].get<double>(), 392.0);
  EXPECT_DOUBLE_EQ(dla2["rhs_equivalents"].get<double>(), steps + parts["jacobian_columns"].get<double>() +
                                                              parts["model_passes"].get<double>() +
                                                              parts["linear_algebra_flops"].get<double>() / 392.0);
}

TEST(Report, AFailingRunIsDataAndTheSweepGoesOn) {
  SweepSpec spec = quick_once();
  // a scene built to fail (lift-off over a crest) before an ordinary one
  spec.scenes = {RB_TEST_DATA "/stop-lift-off.json", "valley-sideways"};
  spec.integrators = {"rk4"};
  spec.hs = {0.01};
  spec.tols.clear();
  const json r = run_report(spec);
  ASSERT_EQ(r["runs"].size(), 2u);
  const json& failed = r["runs"][0];
  EXPECT_EQ(failed["scene"], "stop-lift-off");
  EXPECT_EQ(failed["status"], "lift-off");
  EXPECT_GT(failed["stop_time"].get<double>(), 0.0);
  EXPECT_LT(failed["stop_time"].get<double>(), 2.0);
  EXPECT_GT(failed["steps"].get<long>(), 0);
  // the step after the last valid one is computed, and its first stage finds its start invalid
  EXPECT_EQ(failed["rhs_evals"].get<long>(), 4 * (failed["steps"].get<long>() + 1));
  EXPECT_FALSE(failed["message"].get<std::string>().empty());
  EXPECT_TRUE(failed["error"]["contact"].is_null());
  // the reference failed the same way, and says so instead of stopping the sweep
  EXPECT_EQ(r["references"][0]["kind"], "none");
  EXPECT_NE(r["references"][0]["message"].get<std::string>().find("lift-off"), std::string::npos);
  EXPECT_EQ(r["runs"][1]["status"], "ok");
  EXPECT_TRUE(r["runs"][1]["error"]["contact"].is_number());
}

TEST(Report, EveryShippedSceneHasAReferenceThatAgreesWithItsCrossCheck) {
  SweepSpec spec = preset("default");
  spec.scenes.clear();  // all shipped scenes
  for (const SweepScene& s : prepare_scenes(spec)) {
    ASSERT_NE(s.reference.kind, "none") << s.scene.name << ": " << s.reference.message;
    EXPECT_LT(s.reference.error, 1e-10) << s.scene.name;
    EXPECT_EQ(s.reference.points.size(), s.times.size()) << s.scene.name;
    // closed-form scenes are measured against the closed form, which the
    // computed solution confirms to the same 1e-10
    EXPECT_EQ(s.reference.kind, s.problem.exact() ? "exact" : "computed") << s.scene.name;
  }
}

json without_timings(json r) {
  for (const char* key : {"created", "machine"}) r.erase(key);
  for (json& run : r["runs"]) run.erase("wall_s");
  for (json& d : r["stability"]["drift"]) d.erase("wall_s");
  return r;
}

// Timing runs in rounds of one repeat of every run: each run gets its
// repeats while within its budget, at least one, none when asked for none.
TEST(Report, EveryRunGetsItsRepeatsWithinItsBudget) {
  const auto quiet = [](const std::string&) {};
  SweepSpec spec = quick_once();
  spec.scenes = {"plane"};
  spec.integrators = {"rk4", "odeint-dopri5-adaptive"};
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  for (const auto& [repeats, budget, want] : {std::tuple{3, 100.0, 3u}, {3, 0.0, 1u}, {0, 100.0, 0u}}) {
    spec.repeats = repeats;
    spec.repeat_budget_s = budget;
    const std::vector<RunRecord> runs = run_sweep(spec, scenes, quiet);
    ASSERT_FALSE(runs.empty());
    for (const RunRecord& r : runs) {
      EXPECT_EQ(r.wall_samples.size(), want) << r.method.name << ", repeats " << repeats << ", budget " << budget;
      for (const double w : r.wall_samples) EXPECT_GT(w, 0.0);
    }
  }
}

TEST(Report, MergedShardsEqualTheUnshardedReport) {
  SweepSpec spec = quick_once();
  spec.repeats = 0;
  // a shard cannot extend a ladder it sees only part of: the whole run
  // keeps the ladder as given too (rollbench run --no-finer-steps)
  spec.extend_ladders = false;
  const json whole = run_report(spec);
  std::vector<json> shards;
  for (int i = 0; i < 3; ++i) {
    SweepSpec part = spec;
    part.shard_index = i;
    part.shard_count = 3;
    shards.push_back(run_report(part));
  }
  EXPECT_EQ(without_timings(merge_reports(shards)), without_timings(whole));
  shards[1]["options"]["h"] = {1.0};
  EXPECT_THROW(merge_reports(shards), InputError);
}

// The default ladder: quarter steps from 1 to 2^-8, then halvings to 2^-10;
// a fixed-step task takes t_end / ceil(t_end / h), so a step it records is
// the step it took, and two ladder values with one step are one run.
TEST(Report, TheDefaultLadderHasQuarterStepsAndTasksRecordTheStepTaken) {
  const SweepSpec spec = preset("default");
  ASSERT_EQ(spec.hs.size(), 33u + 2u);
  EXPECT_DOUBLE_EQ(spec.hs[1], std::exp2(-0.25));
  EXPECT_DOUBLE_EQ(spec.hs[32], std::ldexp(1.0, -8));
  EXPECT_DOUBLE_EQ(spec.hs.back(), std::ldexp(1.0, -10));
  EXPECT_DOUBLE_EQ(step_taken(std::exp2(-0.25), 5.0), 5.0 / 6.0);
  EXPECT_DOUBLE_EQ(step_taken(0.25, 5.0), 0.25);
  EXPECT_DOUBLE_EQ(step_taken(-1.0, 5.0), -1.0);  // refused by the method, not here
  SweepSpec one = spec;
  one.scenes = {"plane"};
  one.integrators = {"rk4"};
  one.t_end = 1.0;
  const std::vector<SweepScene> scenes = prepare_scenes(one, false);
  std::vector<double> taken;
  for (const SweepTask& t : sweep_tasks(one, scenes)) {
    const double n = 1.0 / t.h;
    EXPECT_NEAR(n, std::round(n), 1e-9) << t.h;
    EXPECT_EQ(std::count(taken.begin(), taken.end(), t.h), 0) << t.h;
    taken.push_back(t.h);
  }
  EXPECT_LT(taken.size(), spec.hs.size());  // 2^-0.25 and 1 are both one step of 1 on a 1 s run
}

TEST(Report, PresetsAndListsRejectBadInput) {
  EXPECT_THROW(preset("fastest"), InputError);
  EXPECT_EQ(parse_number_list("2^-2..2^-4", "h"), (std::vector<double>{0.25, 0.125, 0.0625}));
  EXPECT_EQ(parse_number_list("2^1..2^-1", "h"), (std::vector<double>{2.0, 1.0, 0.5}));
  EXPECT_EQ(parse_number_list("0.1,1e-3", "h"), (std::vector<double>{0.1, 1e-3}));
  for (const char* bad : {"2^-3..2^-1", "2^-2..2^-4x", "2^-2..2^-99", "2^..2^-3"}) {
    try {
      parse_number_list(bad, "h");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("'h': expected a range like 2^-3..2^-8, got '") + bad + "'");
    }
  }
  try {
    parse_number_list("0.1,abc", "h");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "'h': expected positive numbers separated by commas, got 'abc'");
  }
}

}  // namespace
}  // namespace rb

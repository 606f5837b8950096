// The rollbench command line as a user meets it: exit codes (0 ok, 2 bad
// input naming the key or column, 3 a run stopped early), the CSV it writes
// and the messages on standard error.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/lib/presets.hpp"
#include "integrators/registry.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;

using Outcome = testing::CliOutcome;
using testing::slurp;

Outcome rollbench(const std::string& args) { return testing::run_rollbench(args); }

fs::path temp_file(const std::string& name) { return testing::cli_temp_file(name); }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(Cli, ListShowsEveryRegisteredIntegratorAndTheScenes) {
  const Outcome o = rollbench("list");
  ASSERT_EQ(o.code, 0) << o.err;
  for (const auto& m : registry()) EXPECT_NE(o.out.find("  " + m->name() + " "), std::string::npos) << m->name();
  EXPECT_NE(o.out.find("valley-sideways"), std::string::npos);
  EXPECT_NE(o.out.find("bowl-planar"), std::string::npos);
}

TEST(Cli, ListAlignsItsColumnsForTheLongestNameAndFamily) {
  const Outcome o = rollbench("list");
  ASSERT_EQ(o.code, 0) << o.err;
  // the column "fixed"/"adaptive" starts at one offset on every integrator row,
  // whatever the longest name or family ("discrete-gradient") is
  std::size_t column = std::string::npos;
  int rows = 0;
  for (const std::string& line : lines_of(o.out)) {
    if (line.empty()) break;
    std::size_t at = line.find("  fixed ");
    if (at == std::string::npos) at = line.find("  adaptive ");
    if (at == std::string::npos) continue;
    if (column == std::string::npos) column = at;
    EXPECT_EQ(at, column) << line;
    ++rows;
  }
  EXPECT_EQ(rows, static_cast<int>(registry().size()));
}

TEST(Cli, ListAsMarkdownIsOneRowOfFiveCellsPerMethod) {
  const Outcome o = rollbench("list --markdown");
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> lines = lines_of(o.out);
  ASSERT_EQ(lines.size(), 2 + registry().size());
  EXPECT_EQ(lines[0], "| name | family | order | steps | description |");
  for (std::size_t i = 0; i < registry().size(); ++i) {
    const std::string& row = lines[2 + i];
    EXPECT_EQ(row.rfind("| " + registry()[i]->name() + " | `" + registry()[i]->info().family + "` | ", 0), 0u) << row;
    // six unescaped bars: a '|' in a description is written \|
    int bars = 0;
    for (std::size_t k = 0; k < row.size(); ++k) bars += row[k] == '|' && (k == 0 || row[k - 1] != '\\');
    EXPECT_EQ(bars, 6) << row;
  }
}

TEST(Cli, TrajectoryWritesTheCsvOfFormats) {
  const fs::path csv = temp_file("ok.csv");
  const Outcome o =
      rollbench("trajectory valley-sideways --integrator rkmk4 --h 0.01 --dt-out 0.05 --t-end 1 --out " + csv.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> rows = lines_of(slurp(csv));
  ASSERT_EQ(rows.size(), 1u + 21u);  // header, t = 0, 0.05, ..., 1
  EXPECT_EQ(rows[0],
            "t,x,y,cx,cy,cz,wx,wy,wz,r00,r01,r02,r10,r11,r12,r20,r21,r22,energy,normal_force,spin,rotation_defect");
  EXPECT_EQ(rows.back().substr(0, 2), "1,");
  // 22 columns, full precision
  EXPECT_EQ(std::count(rows[5].begin(), rows[5].end(), ','), 21);
  EXPECT_NE(o.out.find("ok at t = 1"), std::string::npos);
}

TEST(Cli, AdaptiveMethodsTakeTolerances) {
  const fs::path csv = temp_file("adaptive.csv");
  const Outcome o =
      rollbench("trajectory plane --integrator odeint-dopri5-adaptive --rtol 1e-8 --atol 1e-8 --out " + csv.string());
  EXPECT_EQ(o.code, 0) << o.err;
  const Outcome missing = rollbench("trajectory plane --integrator odeint-dopri5-adaptive --out " + csv.string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("'rtol'"), std::string::npos) << missing.err;
}

TEST(Cli, BadInputExitsWithTwoAndNamesThePlace) {
  const fs::path scene = temp_file("bad.json");
  std::ofstream(scene) << R"({"name": "bad", "landscape": "x + sin(y", "ball": {"radius": 0.1, "mass": 1},
    "start": {"contact": [0, 0], "omega": [0, 0, 0]}, "t_end": 1})";
  const fs::path csv = temp_file("bad.csv");
  Outcome o = rollbench("trajectory " + scene.string() + " --integrator rk4 --h 0.01 --out " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'landscape' column 8"), std::string::npos) << o.err;

  o = rollbench("trajectory plane --integrator rk5000 --h 0.01 --out " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'integrator': unknown integrator 'rk5000'"), std::string::npos) << o.err;

  o = rollbench("trajectory plane --integrator rk4 --h 0.1 --dt-out 0.01 --out " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'dt-out'"), std::string::npos) << o.err;

  o = rollbench("trajectory plane --integrator rk4 --h abc --out " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--h"), std::string::npos) << o.err;

  o = rollbench("run --preset quick --shard 3/2 --out " + temp_file("r.json").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'shard'"), std::string::npos) << o.err;
}

TEST(Cli, ARunThatStopsEarlyExitsWithThreeAndKeepsItsRows) {
  const fs::path csv = temp_file("lift.csv");
  const Outcome o =
      rollbench("trajectory " RB_TEST_DATA "/stop-lift-off.json --integrator rkmk4 --h 0.001 --out " + csv.string());
  EXPECT_EQ(o.code, 3);
  EXPECT_NE(o.err.find("lift-off"), std::string::npos) << o.err;
  const std::vector<std::string> rows = lines_of(slurp(csv));
  EXPECT_GT(rows.size(), 10u);   // the rows before the stop are kept
  EXPECT_LT(rows.size(), 202u);  // and none after it
}

TEST(Cli, RunRefusesAMisspeltIntegratorBeforeAnyReference) {
  // chaplygin-bumpy-long's reference takes seconds: nothing of it is made or said
  const Outcome o = rollbench("run --scenes chaplygin-bumpy-long --integrators rkmk4,rkmk44 --out " +
                              temp_file("misspelt.json").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 'integrator': unknown integrator 'rkmk44' (`rollbench list` shows them all)\n");
}

TEST(Cli, RunChecksEverySceneBeforeAnyReferenceNamingTheFile) {
  // the good scene comes first; its reference is neither made nor announced
  const fs::path bad = temp_file("bad-scene.json");
  std::ofstream(bad) << R"({"name": "bad", "description": "a start off its domain", "landscape": "0.1*x^2",
    "domain": [-2, 2, -1, 1], "ball": {"radius": 0.1, "mass": 1.0},
    "start": {"contact": [0.5, 3.0], "velocity": [0.1, 0.0], "spin": 0.0, "orientation": [1, 0, 0, 0]},
    "t_end": 1.0})";
  const Outcome o = rollbench("run --scenes chaplygin-bumpy-long," + bad.string() + " --integrators rk4 --out " +
                              temp_file("bad-scene-report.json").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err.find("reference of"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("rollbench: 'scenes': in " + bad.string() +
                       ": 'start.contact': the start contact (0.5, 3) lies outside the domain [-2, 2] x [-1, 1]\n"),
            std::string::npos)
      << o.err;
}

TEST(Cli, RunTEndShortensEveryScenesRunAndIsChecked) {
  const fs::path report = temp_file("t-end.json");
  const Outcome o =
      rollbench("run --scenes plane --integrators rk4 --h 0.25 --repeats 0 --t-end 1.5 --out " + report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(j.at("options").at("t_end"), 1.5);
  for (const char* bad : {"0", "-1", "inf", "nan"}) {
    const Outcome b = rollbench(std::string("run --scenes plane --t-end ") + bad + " --out " + report.string());
    EXPECT_EQ(b.code, 2) << bad;
    EXPECT_EQ(b.err, "rollbench: 't-end': the end time must be a finite number > 0\n") << bad;
  }
}

TEST(Cli, RunHelpShowsTheDefaultsOfRepeatsAndJobs) {
  const Outcome o = rollbench("run --help");
  EXPECT_EQ(o.code, 0);
  EXPECT_NE(o.out.find("timed repeats per run (default: the preset's; quick 2, default 3, full 7, regime 3)"),
            std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("threads for the accuracy runs (default: 2)"), std::string::npos) << o.out;
}

TEST(Cli, RunWithoutAPresetHasNoStabilityStudy) {
  const fs::path report = temp_file("no-preset.json");
  const Outcome o =
      rollbench("run --scenes plane --integrators rk4,rkmk4 --h 0.25,0.125 --repeats 0 --out " + report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(j.at("preset"), "custom");
  EXPECT_EQ(j.at("options").at("stability").at("enabled"), false);
  EXPECT_TRUE(j.at("stability").at("largest_stable_h").empty());
  EXPECT_TRUE(j.at("stability").at("drift").empty());
  // with the preset named, its study runs (the quick preset has none: checked on default's spec)
  EXPECT_TRUE(preset("default").stability.enabled);
}

TEST(Cli, ALieStepPastTheChartsEdgeIsChartLimitNotDiverged) {
  const fs::path csv = temp_file("chart.csv");
  const Outcome o = rollbench("trajectory chaplygin-valley --integrator rkmk8 --h 0.5 --out " + csv.string());
  EXPECT_EQ(o.code, 3);
  EXPECT_NE(o.err.find("chart-limit: a stage turns the ball by |u| = "), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("past the exponential chart's edge (5.89 rad"), std::string::npos) << o.err;
  // the same step with the Cayley map has no edge to pass: whatever it meets, not this
  const Outcome c = rollbench("trajectory chaplygin-valley --integrator rkmk4-cayley --h 0.5 --out " + csv.string());
  EXPECT_EQ(c.err.find("chart-limit"), std::string::npos) << c.err;
}

TEST(Cli, RunWritesAReportAndAShortTable) {
  const fs::path report = temp_file("report.json");
  const Outcome o = rollbench(
      "run --preset quick --scenes plane --integrators rk4,rkmk4 --h 0.1,0.05,0.025 --repeats 1 "
      "--out " +
      report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("rkmk4"), std::string::npos);
  EXPECT_NE(o.err.find("reference of plane: exact"), std::string::npos) << o.err;
  EXPECT_NE(slurp(report).find("\"schema\": \"rollbench.report/2\""), std::string::npos);
}

TEST(Cli, RunDtOutSetsTheTimedOutputsAndRejectsBadSpacing) {
  const fs::path report = temp_file("dt-out.json");
  const Outcome o = rollbench(
      "run --preset quick --scenes plane --integrators rk4 --h 0.25 --repeats 0 "
      "--no-stability --dt-out 0.5 --out " +
      report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  // plane runs 2 s in the quick preset: outputs 0.5, 1, 1.5, 2
  EXPECT_NE(slurp(report).find("\"timed_outputs\": 4"), std::string::npos);
  for (const char* bad : {"0", "-1", "inf"}) {
    const Outcome b = rollbench(std::string("run --preset quick --dt-out ") + bad + " --out " + report.string());
    EXPECT_EQ(b.code, 2) << bad;
    EXPECT_EQ(b.err, "rollbench: 'dt-out': the output spacing must be a finite number > 0\n") << bad;
  }
}

// --controller: refused when unknown (exit 2, naming the key and the known
// ones); otherwise recorded in the report's options and, per run, the
// controller each method used (filters where the method takes one).
TEST(Cli, RunControllerIsCheckedAndRecorded) {
  const fs::path report = temp_file("controller.json");
  Outcome o = rollbench("run --preset quick --controller p --out " + report.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'controller': unknown step-size controller 'p' (known: constant, library, i, pi, pid)\n");
  o = rollbench(
      "run --preset quick --scenes valley-sideways --integrators rkmk-bs32-adaptive,odeint-dopri5-adaptive,rk4 "
      "--tol 1e-6 --h 0.05 --repeats 1 --no-stability --controller pid --out " +
      report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  std::ifstream in(report);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["options"]["controller"], "pid");
  ASSERT_EQ(j["runs"].size(), 3u);
  for (const auto& run : j["runs"]) {
    const std::string name = run["integrator"];
    const std::string expected = name == "rk4" ? "constant" : name == "odeint-dopri5-adaptive" ? "library" : "pid";
    EXPECT_EQ(run["controller"], expected) << name;
    EXPECT_EQ(run["status"], "ok") << name;
  }
}

// --controller on trajectory, as on run: refused when unknown; the summary
// names the controller the run used, a filter where the method takes one,
// and a filter other than the default changes an RKMK pair's steps.
TEST(Cli, TrajectoryControllerIsCheckedAndRecorded) {
  const fs::path csv = temp_file("controller.csv");
  const std::string common = " --rtol 1e-6 --atol 1e-6 --t-end 2 --out " + csv.string();
  Outcome o = rollbench("trajectory valley-sideways --integrator rkmk-bs32-adaptive --controller p" + common);
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'controller': unknown step-size controller 'p' (known: constant, library, i, pi, pid)\n");
  // the summary's cost line: "  steps N, rejected M, rhs evals K, controller C"
  auto cost_line = [&](const std::string& integrator, const std::string& controller) {
    const Outcome r = rollbench("trajectory valley-sideways --integrator " + integrator +
                                (controller.empty() ? "" : " --controller " + controller) + common);
    EXPECT_EQ(r.code, 0) << r.err;
    for (const std::string& line : lines_of(r.out))
      if (line.rfind("  steps ", 0) == 0) return line;
    ADD_FAILURE() << "no cost line in: " << r.out;
    return std::string();
  };
  const std::string pi = cost_line("rkmk-bs32-adaptive", ""), pid = cost_line("rkmk-bs32-adaptive", "pid");
  EXPECT_EQ(pi.substr(pi.rfind(", controller ")), ", controller pi");
  EXPECT_EQ(pid.substr(pid.rfind(", controller ")), ", controller pid");
  EXPECT_NE(pi.substr(0, pi.find(", rejected")), pid.substr(0, pid.find(", rejected")));
  const std::string library = cost_line("odeint-dopri5-adaptive", ""),
                    kept = cost_line("odeint-dopri5-adaptive", "pid");
  EXPECT_EQ(kept, library);
  EXPECT_EQ(kept.substr(kept.rfind(", controller ")), ", controller library");
}

}  // namespace
}  // namespace rb

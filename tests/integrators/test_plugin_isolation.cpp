// What a plug-in cannot do to `rollbench run` and `trajectory`
// (integrators/steppers/isolated_run.hpp, bench/lib/output_file.hpp): crash
// it, abort it or hang it (each is a status in the report, the rest of the
// sweep is kept), or lose the report with bytes that are not UTF-8 (the
// report is written, valid JSON, with U+FFFD for each bad byte).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "tests/cli_run.hpp"
#include "tests/example_steppers.hpp"

namespace rb {
namespace {

using testing::cli_temp_file;
using testing::example_stepper;
using testing::example_stepper_dir;
using testing::run_rollbench;
using testing::slurp;

std::string steppers(std::initializer_list<const char*> names) {
  std::string out;
  for (const char* name : names) out += " --stepper " + example_stepper(name);
  return out;
}

std::map<std::string, nlohmann::json> runs_by_name(const nlohmann::json& report) {
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& r : report["runs"]) by_name[r["integrator"].get<std::string>()] = r;
  return by_name;
}

const char* const kSweep = "run --preset quick --no-stability --repeats 2 --scenes valley-sideways --h 0.0625 ";

TEST(PluginIsolation, ACrashAnAbortAndAHangAreRowsOfTheReportAndTheSweepGoesOn) {
  const std::filesystem::path report_path = cli_temp_file("isolated.json");
  const testing::CliOutcome o =
      run_rollbench(std::string(kSweep) +
                    "--integrators crash-stepper,abort-stepper,hang-stepper,midpoint-plugin,rk4 --stepper-timeout 2" +
                    steppers({"crash_stepper", "abort_stepper", "hang_stepper", "midpoint_stepper"}) + " --out " +
                    report_path.string());
  ASSERT_EQ(o.code, 0) << o.err;  // failed runs are data: the sweep itself succeeded
  const nlohmann::json report = nlohmann::json::parse(slurp(report_path));
  ASSERT_EQ(report["runs"].size(), 5u);
  std::map<std::string, nlohmann::json> by_name = runs_by_name(report);
  EXPECT_EQ(by_name["crash-stepper"]["status"], "crashed");
  EXPECT_EQ(by_name["crash-stepper"]["message"],
            "stepper 'crash-stepper' crashed: its process was killed by signal 11 (SIGSEGV: Segmentation fault); its "
            "state and cost are lost");
  EXPECT_EQ(by_name["abort-stepper"]["status"], "crashed");
  EXPECT_EQ(by_name["abort-stepper"]["message"],
            "stepper 'abort-stepper' crashed: its process was killed by signal 6 (SIGABRT: Aborted); its state and "
            "cost are lost");
  EXPECT_EQ(by_name["hang-stepper"]["status"], "timeout");
  EXPECT_EQ(by_name["hang-stepper"]["message"],
            "stepper 'hang-stepper' was still running after the wall-clock limit of 2 s (--stepper-timeout) and was "
            "killed; its state and cost are lost");
  for (const char* lost : {"crash-stepper", "abort-stepper", "hang-stepper"}) {
    EXPECT_EQ(by_name[lost]["stop_time"], 0.0) << lost;
    EXPECT_EQ(by_name[lost]["wall_s"]["repeats"], 0) << lost;  // not timed: it would crash or hang again
    EXPECT_TRUE(by_name[lost]["error"]["worst"].is_null()) << lost;
  }
  for (const char* good : {"midpoint-plugin", "rk4"}) {
    EXPECT_EQ(by_name[good]["status"], "ok") << good;
    EXPECT_EQ(by_name[good]["wall_s"]["repeats"], 2) << good;
    EXPECT_GT(by_name[good]["wall_s"]["median"].get<double>(), 0.0) << good;
    EXPECT_TRUE(by_name[good]["error"]["worst"].is_number()) << good;
  }
}

TEST(PluginIsolation, InProcessOnRequestGivesTheSameNumbers) {
  const std::filesystem::path isolated = cli_temp_file("process.json"), in_process = cli_temp_file("none.json");
  const std::string sweep = std::string(kSweep) + "--integrators midpoint-plugin,exp-euler-plugin" +
                            steppers({"midpoint_stepper", "lie_euler_stepper"});
  const testing::CliOutcome a = run_rollbench(sweep + " --out " + isolated.string());
  const testing::CliOutcome b = run_rollbench(sweep + " --stepper-isolation none --out " + in_process.string());
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  std::map<std::string, nlohmann::json> x = runs_by_name(nlohmann::json::parse(slurp(isolated)));
  std::map<std::string, nlohmann::json> y = runs_by_name(nlohmann::json::parse(slurp(in_process)));
  ASSERT_EQ(x.size(), 2u);
  for (auto& [name, run] : x) {
    for (const char* key :
         {"status", "steps", "rhs_evals", "exp_evals", "validity_checks", "error", "error_max", "drift", "final"})
      EXPECT_EQ(run[key], y[name][key]) << name << " " << key;
  }
}

TEST(PluginIsolation, TheIsolationOptionsAreChecked) {
  const testing::CliOutcome a = run_rollbench(
      "trajectory bowl-planar --integrator rk4 --h 0.1 --out /dev/null "
      "--stepper-isolation thread");
  EXPECT_EQ(a.code, 2);
  EXPECT_EQ(a.err,
            "rollbench: 'stepper-isolation': expected process (each plug-in run in a child process) or none "
            "(in-process), got 'thread'\n");
  const testing::CliOutcome b = run_rollbench(
      "trajectory bowl-planar --integrator rk4 --h 0.1 --out /dev/null "
      "--stepper-timeout 0");
  EXPECT_EQ(b.code, 2);
  EXPECT_EQ(b.err,
            "rollbench: 'stepper-timeout': the wall-clock limit of a plug-in run must be a finite number of seconds "
            "> 0\n");
}

TEST(PluginIsolation, ATrajectoryWhosePluginCrashesExitsThreeWithTheSignal) {
  const std::filesystem::path csv = cli_temp_file("crash.csv");
  const testing::CliOutcome o =
      run_rollbench("trajectory valley-sideways --integrator crash-stepper --h 0.0625 --out " + csv.string() +
                    steppers({"crash_stepper"}));
  EXPECT_EQ(o.code, 3);
  EXPECT_EQ(o.err,
            "rollbench: run stopped early at t = 0: crashed: stepper 'crash-stepper' crashed: its process was killed "
            "by signal 11 (SIGSEGV: Segmentation fault); its state and cost are lost\n");
  const std::string text = slurp(csv);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;  // the header and the start: no rows came back
}

TEST(PluginIsolation, ALieViewPluginOffSo3IsTheStatusOffGroupInTheReport) {
  const std::filesystem::path report_path = cli_temp_file("off-group.json");
  const testing::CliOutcome o =
      run_rollbench(std::string(kSweep) + "--integrators off-group-stepper,exp-euler-plugin" +
                    steppers({"off_group_stepper", "lie_euler_stepper"}) + " --out " + report_path.string());
  ASSERT_EQ(o.code, 0) << o.err;
  std::map<std::string, nlohmann::json> by_name = runs_by_name(nlohmann::json::parse(slurp(report_path)));
  EXPECT_EQ(by_name["off-group-stepper"]["status"], "off-group");
  EXPECT_EQ(by_name["off-group-stepper"]["stop_time"], 0.5);
  EXPECT_EQ(by_name["off-group-stepper"]["message"],
            "stepper 'off-group-stepper' (Lie-group view) returned R off SO(3) in the step from t = 0.5: "
            "||R^T R - I||_F = 0.364 > 1e-06");
  EXPECT_EQ(by_name["exp-euler-plugin"]["status"], "ok");
}

TEST(PluginIsolation, AFolderGivenAsStepperIsNamedAsOne) {
  const std::string folder = example_stepper_dir();
  const testing::CliOutcome o = run_rollbench("list --stepper " + folder);
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'stepper': '" + folder + "' is a directory, not a stepper library (give the .so file in it)\n");
}

// Bytes that are not UTF-8, from a plug-in's reason and from a scene path:
// the report is written, strict JSON, each bad byte a U+FFFD; the exit code
// is a normal sweep's (0: failed runs are data).
TEST(PluginIsolation, BytesThatAreNotUtf8DoNotLoseTheReport) {
  const std::filesystem::path report_path = cli_temp_file("utf8.json");
  std::ofstream(report_path) << "{\"an\": \"older report\"}\n";
  const testing::CliOutcome o = run_rollbench(std::string(kSweep) + "--integrators bad-utf8-stepper,rk4" +
                                              steppers({"bad_utf8_stepper"}) + " --out " + report_path.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(report_path));  // throws on invalid UTF-8
  std::map<std::string, nlohmann::json> by_name = runs_by_name(report);
  EXPECT_EQ(by_name["bad-utf8-stepper"]["status"], "error");
  EXPECT_EQ(by_name["bad-utf8-stepper"]["message"],
            "stepper 'bad-utf8-stepper' returned error code 5 at t = 0.5: bad bytes \xEF\xBF\xBD\xEF\xBF\xBD in the "
            "reason");
  EXPECT_EQ(by_name["rk4"]["status"], "ok");

  // a scene file whose path holds the byte 0xFF
  const std::filesystem::path scene = cli_temp_file("scene-\xFF.json");
  std::filesystem::copy_file(std::string(RB_SCENE_DIR) + "/valley-sideways.json", scene,
                             std::filesystem::copy_options::overwrite_existing);
  const std::filesystem::path second = cli_temp_file("utf8-path.json");
  const testing::CliOutcome p = run_rollbench(
      "run --preset quick --no-stability --repeats 1 --h 0.0625 "
      "--integrators rk4 --scenes " +
      scene.string() + " --out " + second.string());
  ASSERT_EQ(p.code, 0) << p.err;
  const nlohmann::json by_path = nlohmann::json::parse(slurp(second));
  const std::string shown = cli_temp_file("scene-\xEF\xBF\xBD.json").string();
  EXPECT_EQ(by_path["options"]["scenes"], nlohmann::json::array({shown}));
  EXPECT_EQ(by_path["runs"][0]["status"], "ok");
  std::filesystem::remove(scene);
}

}  // namespace
}  // namespace rb

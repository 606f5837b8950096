// --stepper on the command line (bench/lib/stepper_option.hpp): the example
// libraries of examples/ swept by `rollbench run` like built-in methods
// (the report measures their declared order), listed by `list`, run by
// `trajectory`; broken ones exit 2 naming the file and the symbol, a
// failing step is a failed run in the report, never a crash of the sweep.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli_run.hpp"
#include "tests/example_steppers.hpp"

namespace rb {
namespace {

using testing::cli_temp_file;
using testing::example_stepper;
using testing::run_rollbench;
using testing::slurp;

const nlohmann::json* order_of(const nlohmann::json& report, const std::string& integrator) {
  for (const auto& o : report["orders"])
    if (o["integrator"] == integrator) return &o;
  return nullptr;
}

TEST(PluginCli, RunSweepsTheExampleSteppersAndMeasuresTheirOrders) {
  const std::filesystem::path report_path = cli_temp_file("report.json");
  const testing::CliOutcome o = run_rollbench(
      "run --preset quick --no-stability --repeats 1 --scenes bowl-planar --h 2^-4..2^-9 "
      "--integrators midpoint-plugin,exp-euler-plugin,midpoint,exp-euler --stepper " +
      example_stepper("midpoint_stepper") + " --stepper " + example_stepper("lie_euler_stepper") + " --out " +
      report_path.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(report_path));
  // each plug-in measures as its built-in twin does (exp-euler's omega
  // errors are above the fit window's 0.1 at these steps: inconclusive)
  for (const auto& [name, twin] :
       {std::pair{"midpoint-plugin", "midpoint"}, std::pair{"exp-euler-plugin", "exp-euler"}}) {
    const nlohmann::json* fit = order_of(report, name);
    const nlohmann::json* twin_fit = order_of(report, twin);
    ASSERT_NE(fit, nullptr) << name;
    ASSERT_NE(twin_fit, nullptr) << twin;
    EXPECT_EQ((*fit)["declared"], (*twin_fit)["declared"]);
    EXPECT_EQ((*fit)["verdict"], (*twin_fit)["verdict"]) << name;
    for (const char* c : {"contact", "centre"})
      EXPECT_NEAR((*fit)["observed"][c].get<double>(), (*twin_fit)["observed"][c].get<double>(), 1e-9) << name << c;
  }
  const nlohmann::json& midpoint_fit = *order_of(report, "midpoint-plugin");
  EXPECT_EQ(midpoint_fit["declared"], 2);
  EXPECT_EQ(midpoint_fit["pass"], true) << midpoint_fit.dump();
  for (const char* c : {"contact", "centre", "omega", "rotation"})
    EXPECT_NEAR(midpoint_fit["observed"][c].get<double>(), 2.0, 0.2) << c;
  const nlohmann::json& euler_fit = *order_of(report, "exp-euler-plugin");
  EXPECT_EQ(euler_fit["declared"], 1);
  EXPECT_NEAR(euler_fit["observed"]["contact"].get<double>(), 1.0, 0.1);
  // the same errors and counts as the built-in midpoint, and timed like it
  std::map<double, nlohmann::json> builtin;
  for (const auto& r : report["runs"])
    if (r["integrator"] == "midpoint") builtin[r["h"].get<double>()] = r;
  int compared = 0;
  for (const auto& r : report["runs"]) {
    EXPECT_EQ(r["status"], "ok") << r.dump();
    EXPECT_EQ(r["wall_s"]["repeats"], 1);
    if (r["integrator"] != "midpoint-plugin") continue;
    EXPECT_EQ(r["family"], "plugin");
    const nlohmann::json& b = builtin.at(r["h"].get<double>());
    EXPECT_EQ(r["error"]["worst"], b["error"]["worst"]);
    EXPECT_EQ(r["error_max"]["worst"], b["error_max"]["worst"]);
    for (const char* count : {"steps", "rhs_evals", "validity_checks"}) EXPECT_EQ(r[count], b[count]) << count;
    ++compared;
  }
  EXPECT_EQ(compared, 6);
}

TEST(PluginCli, ListAndTrajectoryTakeSteppers) {
  const testing::CliOutcome list = run_rollbench("list --stepper " + example_stepper("midpoint_stepper"));
  ASSERT_EQ(list.code, 0) << list.err;
  // its row, the columns' padding (as wide as the widest entry) collapsed
  const std::size_t at = list.out.find("\n  midpoint-plugin ");
  ASSERT_NE(at, std::string::npos) << list.out;
  std::string row;
  for (std::size_t i = at + 3; i < list.out.size() && list.out[i] != '\n'; ++i)
    if (list.out[i] != ' ' || row.back() != ' ') row += list.out[i];
  EXPECT_EQ(row.rfind("midpoint-plugin plugin 2 fixed explicit midpoint rule in C", 0), 0u) << row;
  const std::filesystem::path csv = cli_temp_file("t.csv");
  const testing::CliOutcome t =
      run_rollbench("trajectory valley-sideways --integrator midpoint-plugin --h 0.01 --t-end 1 --out " + csv.string() +
                    " --stepper " + example_stepper("midpoint_stepper"));
  EXPECT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.out.rfind("midpoint-plugin on valley-sideways: ok at t = 1 (101 rows", 0), 0u) << t.out;
  // a failing step: the run stops early (exit 3) with the plug-in's reason
  const testing::CliOutcome f =
      run_rollbench("trajectory valley-sideways --integrator fails-stepper --h 0.0625 --out " + csv.string() +
                    " --stepper " + example_stepper("fails_stepper"));
  EXPECT_EQ(f.code, 3);
  EXPECT_EQ(f.err,
            "rollbench: run stopped early at t = 0.5: error: stepper 'fails-stepper' returned error code 7 at t = 0.5: "
            "the linear solve did not converge (residual 1.0e-03)\n");
}

TEST(PluginCli, AFailingStepperIsAFailedRunInTheReport) {
  const std::filesystem::path report_path = cli_temp_file("failing.json");
  const testing::CliOutcome o = run_rollbench(
      "run --preset quick --no-stability --repeats 1 --scenes valley-sideways --h 0.0625 "
      "--integrators fails-stepper,nan-stepper,rk4 --stepper " +
      example_stepper("fails_stepper") + " --stepper " + example_stepper("nan_stepper") + " --out " +
      report_path.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(report_path));
  ASSERT_EQ(report["runs"].size(), 3u);
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& r : report["runs"]) by_name[r["integrator"].get<std::string>()] = r;
  EXPECT_EQ(by_name["fails-stepper"]["status"], "error");
  EXPECT_EQ(by_name["fails-stepper"]["message"],
            "stepper 'fails-stepper' returned error code 7 at t = 0.5: the linear solve did not converge (residual "
            "1.0e-03)");
  EXPECT_EQ(by_name["fails-stepper"]["stop_time"], 0.5);
  EXPECT_EQ(by_name["nan-stepper"]["status"], "diverged");
  EXPECT_EQ(by_name["nan-stepper"]["stop_time"], 0.5);
  EXPECT_EQ(by_name["rk4"]["status"], "ok");
}

TEST(PluginCli, ABrokenStepperExitsWithTwoNamingTheFileAndTheSymbol) {
  const std::string no_step = example_stepper("no_step_stepper"), bad_abi = example_stepper("bad_abi_stepper"),
                    example = example_stepper("midpoint_stepper");
  const testing::CliOutcome a = run_rollbench("run --preset quick --out x.json --stepper " + no_step);
  EXPECT_EQ(a.code, 2);
  EXPECT_EQ(a.err, "rollbench: 'stepper': '" + no_step +
                       "' does not export 'rollbench_stepper_step' (see integrators/plugin/rollbench_stepper.h)\n");
  const testing::CliOutcome b = run_rollbench("list --stepper " + bad_abi);
  EXPECT_EQ(b.code, 2);
  EXPECT_EQ(b.err, "rollbench: 'stepper': '" + bad_abi +
                       "': rollbench_stepper_abi_version() is 99, this rollbench takes 1 (rebuild it against "
                       "integrators/plugin/rollbench_stepper.h)\n");
  const testing::CliOutcome c = run_rollbench("list --stepper " + example + " --stepper " + example);
  EXPECT_EQ(c.code, 2);
  EXPECT_EQ(c.err, "rollbench: 'stepper': '" + example +
                       "': rollbench_stepper_info(): integrator 'midpoint-plugin' is already registered\n");
  const testing::CliOutcome d = run_rollbench("list --stepper /nonexistent/libx.so");
  EXPECT_EQ(d.code, 2);
  EXPECT_EQ(d.err, "rollbench: 'stepper': '/nonexistent/libx.so': no such file\n");
}

}  // namespace
}  // namespace rb

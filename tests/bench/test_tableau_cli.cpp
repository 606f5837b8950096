// rollbench --tableau FILE as a user meets it: a tableau written to a file
// runs through `rollbench run` and its declared order is measured in the
// report for both rk-<name> and rkmk-<name>; list and trajectory take it
// too; a bad file exits with 2 and names the file, the key and the problem.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bench/lib/tableau_option.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;
using robustness::slurp;

fs::path scratch(const std::string& name) { return robustness::temp_path("tableau-" + name); }

fs::path tableau_file(const std::string& name, const std::string& text) {
  const fs::path p = scratch(name);
  std::ofstream(p) << text;
  return p;
}

// Ralston's third-order method as in docs/formats.md, and the Bogacki-Shampine
// 3(2) pair in the seminar's layout.
const char* const kRalston = R"json({"name": "ral3", "order": 3, "c": [0, 0.5, 0.75],
  "A": [[0, 0, 0], [0.5, 0, 0], [0, 0.75, 0]],
  "b": [0.2222222222222222, 0.3333333333333333, 0.4444444444444444], "source": "Ralston (1962)"})json";
const char* const kBs32 = R"({"name": "bs-file", "order": 3, "err_order": 2,
  "butcher": [[0, 0, 0, 0, 0], [0.5, 0.5, 0, 0, 0], [0.75, 0, 0.75, 0, 0],
              [1, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0],
              [0, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0]],
  "b_err": [0.2916666666666667, 0.25, 0.3333333333333333, 0.125]})";

TEST(TableauCli, RunMeasuresTheDeclaredOrderOfRkAndRkmk) {
  const fs::path report = scratch("report.json");
  const robustness::CliOutcome r = robustness::rollbench(
      "run --preset quick --scenes bowl-planar --h 2^-3..2^-7 --tol 1e-5,1e-7 "
      "--repeats 1 --no-stability --tableau " +
      tableau_file("ral3.json", kRalston).string() + " --tableau " + tableau_file("bs.json", kBs32).string() +
      " --integrators rk-ral3,rkmk-ral3,rk-bs-file,rkmk-bs-file,rk-bs-file-adaptive,"
      "rkmk-bs-file-adaptive --out " +
      report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(report));
  std::map<std::string, const nlohmann::json*> orders;
  for (const auto& o : j.at("orders")) orders[o.at("integrator").get<std::string>()] = &o;
  for (const char* name : {"rk-ral3", "rkmk-ral3", "rk-bs-file", "rkmk-bs-file"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(orders.count(name));
    const nlohmann::json& o = *orders[name];
    EXPECT_EQ(o.at("declared"), 3);
    EXPECT_NEAR(o.at("observed").at("contact").get<double>(), 3.0, 0.3);
    EXPECT_EQ(o.at("pass"), true);
  }
  // the tableau is each run's fact: rk-X on the flat view and rkmk-X on SO(3)
  // share it, which is what the analysis pairs them by (tests/analysis)
  for (const auto& run : j.at("runs")) {
    const std::string name = run.at("integrator").get<std::string>();
    SCOPED_TRACE(name);
    const bool lie = name.rfind("rkmk-", 0) == 0;
    EXPECT_EQ(run.at("on_group").get<bool>(), lie);
    EXPECT_EQ(run.at("tableau").get<std::string>(), name.find("ral3") != std::string::npos ? "ral3" : "bs-file");
  }
  // the adaptive variants run to the end and meet a tighter tolerance with a smaller error
  for (const char* name : {"rk-bs-file-adaptive", "rkmk-bs-file-adaptive"}) {
    SCOPED_TRACE(name);
    std::map<double, double> error_at;
    for (const auto& run : j.at("runs"))
      if (run.at("integrator") == name) {
        EXPECT_EQ(run.at("status"), "ok");
        error_at[run.at("rtol").get<double>()] = run.at("error").at("contact").get<double>();
      }
    ASSERT_EQ(error_at.size(), 2u);
    EXPECT_LT(error_at[1e-7], error_at[1e-5] / 10);
  }
}

TEST(TableauCli, TheFilesMethodsJoinAPresetsListButNotTheUsersChoice) {
  const std::vector<std::string> mine = {"rk-x", "rkmk-x"};
  EXPECT_EQ(with_tableau_methods({"rk4", "rk-x"}, false, mine), (std::vector<std::string>{"rk4", "rk-x", "rkmk-x"}));
  EXPECT_EQ(with_tableau_methods({"rk4"}, true, mine), (std::vector<std::string>{"rk4"}));
  EXPECT_TRUE(with_tableau_methods({}, false, mine).empty());  // empty: everything registered, theirs included
}

TEST(TableauCli, ListAndTrajectoryTakeTheFileToo) {
  const std::string file = tableau_file("ral3.json", kRalston).string();
  const robustness::CliOutcome list = robustness::rollbench("list --tableau " + file);
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_NE(list.out.find("  rk-ral3 "), std::string::npos);
  EXPECT_NE(list.out.find("  rkmk-ral3 "), std::string::npos);
  const robustness::CliOutcome traj = robustness::rollbench(
      "trajectory plane --tableau " + file + " --integrator rkmk-ral3 --h 0.01 --out " + scratch("ral3.csv").string());
  ASSERT_EQ(traj.code, 0) << traj.err;
  EXPECT_NE(traj.out.find("rkmk-ral3 on plane: ok"), std::string::npos) << traj.out;
}

// The note a file gets whose A, b and c are a shipped tableau's.
std::string twin_note(const std::string& file, const std::string& name) {
  return "rollbench: note: tableau file '" + file + "': tableau '" + name +
         "' has the A, b and c of the shipped tableau 'bs32' (Bogacki & Shampine, A 3(2) pair of Runge-Kutta "
         "formulas, Appl. Math. Lett. 2 (1989); built in as rk-bs32-adaptive): the same method under another "
         "name\n";
}

// A file that types in a shipped tableau (Bogacki-Shampine, rounded to 16
// digits; and Ralston's third-order method, which is BS32's propagated
// solution) loads, with a note naming the built-in it duplicates; Heun's
// method with its weights moved by 1e-9 (order 1, as the file says) gets none.
TEST(TableauCli, AFileTypingInAShippedTableauGetsANoteNamingIt) {
  const std::string bs = tableau_file("bs-twin.json", kBs32).string();
  const robustness::CliOutcome twin = robustness::rollbench("list --tableau " + bs);
  ASSERT_EQ(twin.code, 0) << twin.err;
  EXPECT_EQ(twin.err, twin_note(bs, "bs-file"));
  const std::string ral3 = tableau_file("ral3-twin.json", kRalston).string();
  const robustness::CliOutcome ralston = robustness::rollbench("list --tableau " + ral3);
  EXPECT_EQ(ralston.err, twin_note(ral3, "ral3"));
  const char* const kNearHeun = R"({"name": "near-heun", "order": 1, "c": [0, 1], "A": [[0, 0], [1, 0]],
    "b": [0.500000001, 0.499999999]})";
  const robustness::CliOutcome near =
      robustness::rollbench("list --tableau " + tableau_file("near-heun.json", kNearHeun).string());
  EXPECT_EQ(near.code, 0) << near.err;
  EXPECT_EQ(near.err, "");
}

TEST(TableauCli, ABadFileExitsWithTwoNamingTheFileKeyAndTree) {
  const std::string bad = tableau_file("bad.json", std::string(kRalston).replace(
                                                       std::string(kRalston).find("\"order\": 3"), 10, "\"order\": 4"))
                              .string();
  robustness::CliOutcome r = robustness::rollbench("list --tableau " + bad);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rollbench: tableau file '" + bad +
                       "': 'order': tableau 'ral3' declares order 4 but satisfies the order conditions only to order 3 "
                       "(tree [τ³] of order 4: Phi = 0.229166666666667, 1/gamma = 0.25, residual -2.083e-02)\n");
  // a name that is taken: rk-bs32-adaptive (its flat twin first) is built in
  const std::string clash =
      tableau_file("clash.json", std::string(kBs32).replace(std::string(kBs32).find("bs-file"), 7, "bs32")).string();
  r = robustness::rollbench("run --preset quick --tableau " + clash + " --out " + scratch("never.json").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rollbench: tableau file '" + clash +
                       "': 'name': integrator 'rk-bs32-adaptive' is already registered; rename the tableau\n");
  // the same file twice clashes with itself
  const std::string ok = tableau_file("ral3.json", kRalston).string();
  r = robustness::rollbench("list --tableau " + ok + " --tableau " + ok);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, twin_note(ok, "ral3") + "rollbench: tableau file '" + ok +
                       "': 'name': integrator 'rk-ral3' is already registered; "
                       "rename the tableau\n");
  // a file that is not there
  r = robustness::rollbench("trajectory plane --tableau /nonexistent.json --integrator rk4 --h 0.1 --out " +
                            scratch("x.csv").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "rollbench: 'tableau': cannot read the tableau file '/nonexistent.json' (No such file or directory)\n");
}

}  // namespace
}  // namespace rb

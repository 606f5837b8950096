// `rollbench score` as a user meets it: the CSV `rollbench trajectory`
// writes for one run of a sweep scores to that run's error, error_max and
// drift in the report; a bad CSV exits 2 naming the line and the column.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli_run.hpp"

namespace rb {
namespace {

using testing::cli_temp_file;
using testing::run_rollbench;
using testing::slurp;

TEST(ScoreCli, ScoringTheTrajectoryOfARunReproducesItsReportEntry) {
  const std::filesystem::path report_path = cli_temp_file("report.json"), csv = cli_temp_file("t.csv"),
                              score_path = cli_temp_file("score.json");
  const testing::CliOutcome run = run_rollbench(
      "run --preset quick --no-stability --repeats 1 --scenes chaplygin-valley "
      "--integrators rk4 --h 0.03125 --out " +
      report_path.string());
  ASSERT_EQ(run.code, 0) << run.err;
  const testing::CliOutcome trajectory = run_rollbench(
      "trajectory chaplygin-valley --integrator rk4 --h 0.03125 --dt-out 0.25 "
      "--t-end 2 --out " +
      csv.string());
  ASSERT_EQ(trajectory.code, 0) << trajectory.err;
  const testing::CliOutcome score =
      run_rollbench("score chaplygin-valley " + csv.string() + " --t-end 2 --out " + score_path.string());
  ASSERT_EQ(score.code, 0) << score.err;
  EXPECT_EQ(score.err, "rollbench: timing is the user's: score measures accuracy and drift only (status ok)\n");

  const nlohmann::json report = nlohmann::json::parse(slurp(report_path));
  const nlohmann::json& expected = report["runs"][0];
  const nlohmann::json got = nlohmann::json::parse(slurp(score_path));
  EXPECT_EQ(got["schema"], "rollbench.score/1");
  EXPECT_EQ(got["reference"]["method"], report["references"][0]["method"]);
  for (const char* field : {"error", "error_max"})
    for (const char* c : {"contact", "centre", "omega", "rotation", "worst"})
      EXPECT_NEAR(got[field][c].get<double>(), expected[field][c].get<double>(),
                  1e-9 * expected[field][c].get<double>())
          << field << "." << c;
  for (const char* d : {"energy", "rotation_defect"})
    EXPECT_NEAR(got["drift"][d].get<double>(), expected["drift"][d].get<double>(),
                1e-9 * expected["drift"][d].get<double>())
        << d;
}

TEST(ScoreCli, ABadCsvExitsWithTwoNamingTheLineAndTheColumn) {
  const std::filesystem::path csv = cli_temp_file("bad.csv");
  std::ofstream(csv) << "t,x,y\n0,0,0\n";
  const testing::CliOutcome o = run_rollbench("score plane " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: '" + csv.string() +
                       "': line 1, column 4 (cx): missing column 'cx'; expected the header "
                       "'t,x,y,cx,cy,cz,wx,wy,wz,r00,r01,r02,r10,r11,r12,r20,r21,r22,energy,normal_force,spin,"
                       "rotation_defect'\n");
  for (const char* value : {"-1", "0", "inf", "nan"}) {
    const testing::CliOutcome t_end = run_rollbench("score plane " + csv.string() + " --t-end " + value);
    EXPECT_EQ(t_end.code, 2) << value;
    EXPECT_EQ(t_end.err, "rollbench: 't-end': the end time must be a finite number > 0\n") << value;
  }
  const testing::CliOutcome dt_out = run_rollbench("score plane " + csv.string() + " --dt-out -0.25");
  EXPECT_EQ(dt_out.err, "rollbench: 'dt-out': the output spacing must be a finite number > 0\n");
  const testing::CliOutcome missing = run_rollbench("score plane /nonexistent/t.csv");
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(missing.err,
            "rollbench: 'trajectory': cannot read the trajectory '/nonexistent/t.csv' (No such file or directory)\n");
}

}  // namespace
}  // namespace rb

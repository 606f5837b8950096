// `rollbench score` as a user meets it: the CSV `rollbench trajectory`
// writes for one run of a sweep scores to that run's error, error_max and
// drift in the report; a bad CSV exits 2 naming the line and the column.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

namespace rb {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) {
  return fs::temp_directory_path() / ("rb-score-cli-" + std::to_string(::getpid()) + "-" + name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Outcome {
  int code;
  std::string out, err;
};

Outcome rollbench(const std::string& args) {
  const fs::path out = temp_file("stdout"), err = temp_file("stderr");
  const std::string command = std::string(RB_ROLLBENCH_EXE) + " " + args + " > " + out.string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

TEST(ScoreCli, ScoringTheTrajectoryOfARunReproducesItsReportEntry) {
  const fs::path report_path = temp_file("report.json"), csv = temp_file("t.csv"), score_path = temp_file("score.json");
  const Outcome run = rollbench("run --preset quick --no-stability --repeats 1 --scenes chaplygin-valley "
                                "--integrators rk4 --h 0.03125 --out " + report_path.string());
  ASSERT_EQ(run.code, 0) << run.err;
  const Outcome trajectory = rollbench("trajectory chaplygin-valley --integrator rk4 --h 0.03125 --dt-out 0.25 "
                                       "--t-end 2 --out " + csv.string());
  ASSERT_EQ(trajectory.code, 0) << trajectory.err;
  const Outcome score = rollbench("score chaplygin-valley " + csv.string() + " --t-end 2 --out " + score_path.string());
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
    EXPECT_NEAR(got["drift"][d].get<double>(), expected["drift"][d].get<double>(), 1e-9 * expected["drift"][d].get<double>())
        << d;
}

TEST(ScoreCli, ABadCsvExitsWithTwoNamingTheLineAndTheColumn) {
  const fs::path csv = temp_file("bad.csv");
  std::ofstream(csv) << "t,x,y\n0,0,0\n";
  const Outcome o = rollbench("score plane " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: '" + csv.string() +
                       "': line 1, column 4 (cx): missing column 'cx'; expected the header "
                       "'t,x,y,cx,cy,cz,wx,wy,wz,r00,r01,r02,r10,r11,r12,r20,r21,r22,energy,normal_force,spin,"
                       "rotation_defect'\n");
  const Outcome missing = rollbench("score plane /nonexistent/t.csv");
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(missing.err, "rollbench: 'trajectory': cannot open '/nonexistent/t.csv' for reading\n");
}

}  // namespace
}  // namespace rb

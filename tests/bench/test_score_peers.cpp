// `rollbench score --peers`: another program's solves (a peer file,
// docs/formats.md "Peer runs") become report runs with the errors `score`
// gives their trajectories; a malformed peer file exits 2 naming the key.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli_run.hpp"

namespace rb {
namespace {

using json = nlohmann::json;
using testing::cli_temp_file;
using testing::run_rollbench;
using testing::slurp;

// A peer file with one solve: the trajectory an adaptive rollbench method wrote.
json peer_file(const std::filesystem::path& csv) {
  json run = {{"scene", "plane"},
              {"integrator", "peer-dp54"},
              {"family", "peer"},
              {"declared_order", 5},
              {"declared_order_text", "5(4)"},
              {"needs_jacobian", false},
              {"rtol", 1e-6},
              {"atol", 1e-6},
              {"status", "ok"},
              {"message", ""},
              {"trajectory", csv.filename().string()},
              {"wall_s", {0.002, 0.001, 0.003}},
              {"steps", 40},
              {"rhs_evals", 280},
              {"jacobian_evals", 0},
              {"validity_checks", 9}};
  return {{"schema", "rollbench.peers/1"},
          {"peer", "test"},
          {"t_end", 2.0},
          {"dt_out", nullptr},
          {"rhs_cost", {{{"scene", "plane"}, {"python_s_per_call", 1e-6}}}},
          {"runs", {run}}};
}

TEST(ScorePeers, APeersSolveIsAReportRunWithTheErrorsScoreGivesIt) {
  const std::filesystem::path csv = cli_temp_file("peer.csv"), peers = cli_temp_file("peers.json");
  const std::filesystem::path report = cli_temp_file("peer-report.json"), score = cli_temp_file("peer-score.json");
  ASSERT_EQ(run_rollbench("trajectory plane --integrator rkmk-dp54-adaptive --rtol 1e-6 --atol 1e-6 --dt-out 0.25 "
                          "--t-end 2 --out " +
                          csv.string())
                .code,
            0);
  std::ofstream(peers) << peer_file(csv).dump();
  const testing::CliOutcome o = run_rollbench("score --peers " + peers.string() + " --out " + report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  ASSERT_EQ(run_rollbench("score plane " + csv.string() + " --t-end 2 --out " + score.string()).code, 0);
  const json r = json::parse(slurp(report)), s = json::parse(slurp(score));
  ASSERT_EQ(r["runs"].size(), 1u);
  const json& run = r["runs"][0];
  EXPECT_EQ(run["integrator"], "peer-dp54");
  EXPECT_EQ(run["status"], "ok");
  EXPECT_EQ(run["error"], s["error"]);
  EXPECT_EQ(run["error_max"], s["error_max"]);
  EXPECT_EQ(run["drift"], s["drift"]);
  EXPECT_EQ(run["wall_s"]["median"], 0.002);
  EXPECT_EQ(run["rhs_evals"], 280);
  EXPECT_TRUE(run["rejected"].is_null());
  EXPECT_DOUBLE_EQ(run["peer"]["rhs_cost_s"].get<double>(), 280e-6);
  EXPECT_EQ(run["peer"]["declared_order_text"], "5(4)");
  EXPECT_EQ(run["timed_outputs"], 8);
  EXPECT_EQ(r["peers"][0]["peer"], "test");
  ASSERT_EQ(r["tolerance_fits"].size(), 1u);
  EXPECT_TRUE(r["tolerance_fits"][0]["step_order"]["slope"].is_null());  // one run: no line
}

TEST(ScorePeers, AMalformedPeerFileNamesTheKey) {
  const std::filesystem::path csv = cli_temp_file("peer-bad.csv"), peers = cli_temp_file("peers-bad.json");
  json p = peer_file(csv);
  p["runs"][0].erase("steps");
  std::ofstream(peers) << p.dump();
  testing::CliOutcome o =
      run_rollbench("score --peers " + peers.string() + " --out " + cli_temp_file("x.json").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 'runs[0].steps': '" + peers.string() + "': is missing\n");
  p = peer_file(csv);
  p["runs"][0]["status"] = "fine";
  std::ofstream(peers) << p.dump();
  o = run_rollbench("score --peers " + peers.string() + " --out " + cli_temp_file("x.json").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'runs[0].status'"), std::string::npos) << o.err;
  o = run_rollbench("score plane " + csv.string() + " --into r.json");
  EXPECT_EQ(o.err, "rollbench: 'into': goes with --peers\n");
}

// issue 32: a peer file's trajectory is a path inside the peer file's own
// folder, a regular file; nothing else is opened, and no content is quoted.
TEST(ScorePeers, ATrajectoryOutsideThePeerFilesFolderOrNotARegularFileIsRefused) {
  namespace fs = std::filesystem;
  const fs::path dir = cli_temp_file("peer-confined"), outside = cli_temp_file("peer-secret.txt");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(outside) << "the-secret-content\n";
  fs::create_symlink(outside, dir / "link-out.csv");
  fs::create_symlink("/dev/zero", dir / "zero.csv");
  ASSERT_EQ(::mkfifo((dir / "fifo.csv").c_str(), 0600), 0);
  const fs::path peers = dir / "peers.json";
  auto refusal = [&](const std::string& trajectory) {
    json p = peer_file(dir / "unused.csv");
    p["runs"][0]["trajectory"] = trajectory;
    std::ofstream(peers) << p.dump();
    const testing::CliOutcome o =
        run_rollbench("score --peers " + peers.string() + " --out " + cli_temp_file("x.json").string());
    EXPECT_EQ(o.code, 2) << trajectory << ": " << o.err;
    EXPECT_EQ(o.err.find("the-secret-content"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("'runs[0].trajectory'"), std::string::npos) << o.err;
    return o.err;
  };
  const std::string inside = "' is not a path inside the peer file's folder";
  EXPECT_NE(refusal("../" + outside.filename().string()).find("'../" + outside.filename().string() + inside),
            std::string::npos);
  EXPECT_NE(refusal(outside.string()).find("'" + outside.string() + inside), std::string::npos);
  EXPECT_NE(refusal("link-out.csv").find("'link-out.csv' leads out of the peer file's folder"), std::string::npos);
  EXPECT_NE(refusal("zero.csv").find("'zero.csv' leads out of the peer file's folder"), std::string::npos);
  EXPECT_NE(refusal("fifo.csv")
                .find("'" + fs::weakly_canonical(dir / "fifo.csv").string() +
                      "' is a FIFO; inputs are read only from regular files"),
            std::string::npos);  // opened without blocking: a FIFO never hangs it
  fs::remove_all(dir);
  fs::remove(outside);
}

}  // namespace
}  // namespace rb

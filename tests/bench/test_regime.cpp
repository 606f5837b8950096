// The regime study: its grid text (every bad grid named with the axis and
// the value), the scenes it generates (checked as scene files are, the
// moments as docs/usage.md gives them) and the report's "regime" section,
// which shards carry into the merge.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bench/lib/presets.hpp"
#include "bench/lib/regime_scenes.hpp"
#include "bench/lib/report.hpp"
#include "problems/input_error.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

using json = nlohmann::json;

std::string grid_error(const std::string& text) {
  try {
    parse_regime_grid(text, default_regime_grid());
  } catch (const InputError& e) {
    return e.what();
  }
  return "(parsed)";
}

TEST(RegimeGrid, AxesGivenReplaceThePresetsAndTheRestStay) {
  const RegimeGrid g = parse_regime_grid("spin=0.1,50;t_end=2", default_regime_grid());
  EXPECT_EQ(g.spin, (std::vector<double>{0.1, 50.0}));
  EXPECT_EQ(g.t_end, (std::vector<double>{2.0}));
  EXPECT_EQ(g.inertia, default_regime_grid().inertia);
  EXPECT_EQ(g.roughness, default_regime_grid().roughness);
  EXPECT_EQ(parse_regime_grid("full", default_regime_grid()).t_end, (std::vector<double>{1, 10, 100, 1000}));
  EXPECT_EQ(regime_cells(default_regime_grid()).size(), 36u);
  EXPECT_EQ(regime_cells(full_regime_grid()).size(), 320u);
}

TEST(RegimeGrid, BadGridsNameTheAxisAndTheValue) {
  EXPECT_EQ(grid_error(""), "'regime': the grid is empty (give default, full or AXIS=V1,V2;...)");
  EXPECT_EQ(grid_error("spin"),
            "'regime': expected AXIS=V1,V2,... for each axis, separated by ';' (or default, full), got 'spin'");
  EXPECT_EQ(grid_error("mass=1"), "'regime': unknown axis 'mass' (known: inertia, spin, roughness, t_end)");
  EXPECT_EQ(grid_error("spin=1;spin=2"), "'regime': the axis spin is given twice");
  EXPECT_EQ(grid_error("spin=1,x"), "'regime': spin: expected finite numbers separated by commas, got '1,x'");
  EXPECT_EQ(grid_error("spin=1,"), "'regime': spin: expected finite numbers separated by commas, got '1,'");
  EXPECT_EQ(grid_error("t_end=inf"), "'regime': t_end: expected finite numbers separated by commas, got 'inf'");
  EXPECT_EQ(grid_error("spin="), "'regime': spin: the axis has no values");
  EXPECT_EQ(grid_error("inertia=0.5"),
            "'regime': inertia: the ratio 0.5 is outside [1, 3] (1: the homogeneous ball; above 3 the moments "
            "break the triangle inequality)");
  EXPECT_EQ(grid_error("inertia=3.01"),
            "'regime': inertia: the ratio 3.01 is outside [1, 3] (1: the homogeneous ball; above 3 the moments "
            "break the triangle inequality)");
  EXPECT_EQ(grid_error("spin=-1"), "'regime': spin: -1 is negative (expected a number >= 0)");
  EXPECT_EQ(grid_error("roughness=-0.1"), "'regime': roughness: -0.1 is negative (expected a number >= 0)");
  EXPECT_EQ(grid_error("t_end=0"), "'regime': t_end: 0 is not > 0");
  EXPECT_EQ(grid_error("spin=5,5.0000001"),
            "'regime': spin: the value 5 is given twice (values must differ in 6 digits)");
}

TEST(RegimeScenes, MomentsKeepTheMeanAndReachTheTriangleEdge) {
  EXPECT_TRUE(regime_moments(1.0).empty());  // the homogeneous ball: no "inertia" key
  const std::vector<double> chaplygin = regime_moments(2.2);
  ASSERT_EQ(chaplygin.size(), 3u);
  // the chaplygin scenes' moments
  EXPECT_NEAR(chaplygin[0], 0.0025, 1e-15);
  EXPECT_NEAR(chaplygin[1], 0.004, 1e-15);
  EXPECT_NEAR(chaplygin[2], 0.0055, 1e-15);
  const std::vector<double> edge = regime_moments(3.0);
  EXPECT_NEAR(edge[0] + edge[1] + edge[2], 3 * 0.4 * 0.1 * 0.1, 1e-15);  // the mean of 2/5 m r^2
  EXPECT_NEAR(edge[2], edge[0] + edge[1], 1e-15);
  EXPECT_NEAR(edge[2] / edge[0], 3.0, 1e-12);
}

TEST(RegimeScenes, EveryCellIsAValidSceneWithItsCoordinates) {
  const RegimeGrid grid = default_regime_grid();
  const std::vector<Scene> scenes = regime_scenes(grid);
  const std::vector<RegimeCell> cells = regime_cells(grid);
  ASSERT_EQ(scenes.size(), cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Scene& s = scenes[i];
    EXPECT_EQ(s.name, cells[i].scene);
    EXPECT_EQ(s.t_end, cells[i].t_end);
    EXPECT_EQ(s.start.spin, cells[i].spin);
    EXPECT_NEAR(s.params.at("b") * s.params.at("k"), cells[i].roughness, 1e-15);
    EXPECT_EQ(s.ball.inertia.has_value(), cells[i].inertia != 1.0) << s.name;
    EXPECT_EQ(make_problem(s).model().anisotropic(), cells[i].inertia != 1.0) << s.name;
  }
  EXPECT_EQ(cells.front().scene, "regime-i1-s0.1-r0-t1");
  EXPECT_EQ(cells.back().scene, "regime-i3-s50-r0.3-t10");
}

TEST(RegimeScenes, ACellTheSceneCheckRefusesIsAnErrorNamingIt) {
  // bumps of slope 100: the start sits on a crest curved so sharply that
  // gravity cannot hold the rolling ball to it
  try {
    regime_scenes(parse_regime_grid("inertia=1;spin=5;roughness=100;t_end=1", default_regime_grid()));
    FAIL() << "a scene the ball does not fit was generated";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("'regime': the cell inertia 1, spin 5 rad/s, roughness 100, t_end 1 makes "
                                          "no valid scene: 'start': the ball leaves the surface at once: the normal "
                                          "force F . N = ",
                                          0),
              0u)
        << e.what();
  }
}

TEST(RegimePreset, GeneratesItsScenesWithoutAStabilityStudy) {
  const SweepSpec spec = preset("regime");
  ASSERT_TRUE(spec.regime.has_value());
  EXPECT_TRUE(spec.scenes.empty());
  EXPECT_FALSE(spec.stability.enabled);
  const std::vector<SweepScene> scenes = prepare_scenes(spec, false);
  ASSERT_EQ(scenes.size(), 36u);
  EXPECT_EQ(scenes[5].scene.name, regime_cells(*spec.regime)[5].scene);
}

// A small grid through the command line: the report's regime section, and
// two shards that merge into it.
TEST(RegimeCli, TheReportRecordsTheGridAndShardsMergeIntoIt) {
  const std::string common =
      "run --regime 'inertia=1,3;spin=5;roughness=0.3;t_end=0.5' --integrators rk4,rkmk4 --h 2^-3..2^-5 "
      "--repeats 1 --out ";
  const auto whole = testing::cli_temp_file("regime-whole.json");
  testing::CliOutcome o = testing::run_rollbench(common + whole.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const json report = read_report(whole.string());
  EXPECT_EQ(report.at("preset"), "regime");
  const json& cells = report.at("regime").at("cells");
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].at("scene"), "regime-i1-s5-r0.3-t0.5");
  EXPECT_EQ(cells[0].at("moments"), nullptr);
  EXPECT_EQ(cells[1].at("inertia"), 3.0);
  EXPECT_EQ(cells[1].at("roughness"), 0.3);
  EXPECT_NEAR(cells[1].at("amplitude").get<double>(), 0.1, 1e-15);
  // rolling at 0.5 m/s (5 rad/s) with a spin of 5 about the normal: |omega0| = 5 sqrt(2)
  EXPECT_NEAR(cells[1].at("omega0").get<double>(), 5.0 * std::sqrt(2.0), 1e-9);
  EXPECT_EQ(report.at("options").at("regime").at("t_end"), json({0.5}));
  EXPECT_EQ(report.at("references")[1].at("r_feeds_back"), true);
  EXPECT_EQ(report.at("references")[0].at("r_feeds_back"), false);
  EXPECT_EQ(report.at("runs").size(), 2u * 2u * 3u);

  std::vector<json> shards;
  for (int i = 0; i < 2; ++i) {
    const auto path = testing::cli_temp_file("regime-shard-" + std::to_string(i) + ".json");
    o = testing::run_rollbench(common + path.string() + " --shard " + std::to_string(i) + "/2");
    ASSERT_EQ(o.code, 0) << o.err;
    shards.push_back(read_report(path.string()));
  }
  const json merged = merge_reports(shards);
  EXPECT_EQ(merged.at("regime"), report.at("regime"));
  EXPECT_EQ(merged.at("runs").size(), report.at("runs").size());

  // shards of two grids are two sweeps
  const auto other = testing::cli_temp_file("regime-other.json");
  o = testing::run_rollbench(
      "run --regime 'inertia=1,2;spin=5;roughness=0.3;t_end=0.5' --integrators rk4,rkmk4 --h 2^-3..2^-5 "
      "--repeats 1 --shard 1/2 --out " +
      other.string());
  ASSERT_EQ(o.code, 0) << o.err;
  try {
    merge_reports({shards[0], read_report(other.string())});
    FAIL() << "shards of two grids merged";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "'reports': the reports come from different sweeps (their options differ)");
  }
  for (const auto& p : {whole, other}) std::filesystem::remove(p);
}

TEST(RegimeCli, TheGridGoesWithTheRegimePresetAndNoScenes) {
  testing::CliOutcome o = testing::run_rollbench("run --preset quick --regime default --out /dev/null");
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 'regime': the grid goes with --preset regime (or no preset), not 'quick'\n");
  o = testing::run_rollbench("run --preset regime --scenes plane --out /dev/null");
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'scenes': the regime study generates its scenes from its grid (--regime): give no --scenes\n");
  o = testing::run_rollbench("run --regime 'inertia=4' --out /dev/null");
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err,
            "rollbench: 'regime': inertia: the ratio 4 is outside [1, 3] (1: the homogeneous ball; above 3 the "
            "moments break the triangle inequality)\n");
}

TEST(RegimeScenes, ALongHorizonMakesASafeSceneName) {
  // "%.6g" writes 1e6 as "1e+06", and a scene name takes no '+'
  const std::vector<Scene> scenes =
      regime_scenes(parse_regime_grid("inertia=1;spin=5;roughness=0.1;t_end=1e6", default_regime_grid()));
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_NE(scenes[0].name.find("1e06"), std::string::npos) << scenes[0].name;
  EXPECT_EQ(scenes[0].name.find('+'), std::string::npos) << scenes[0].name;
}

}  // namespace
}  // namespace rb

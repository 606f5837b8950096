// The regime study: its grid text (every bad grid named with the axis and
// the value), the scenes it generates (checked as scene files are, the
// moments as docs/usage.md gives them) and the report's "regime" section,
// which shards carry into the merge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "bench/lib/presets.hpp"
#include "bench/lib/regime_scenes.hpp"
#include "bench/lib/report.hpp"
#include "integrators/registry.hpp"
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
  EXPECT_EQ(regime_cells(default_regime_grid()).size(), 72u);
  EXPECT_EQ(regime_cells(full_regime_grid()).size(), 2880u);
  EXPECT_TRUE(g.held_out);
  const RegimeGrid without = parse_regime_grid("bowl=0.5,2;speed=0.1;held_out=none", default_regime_grid());
  EXPECT_EQ(without.bowl, (std::vector<double>{0.5, 2.0}));
  EXPECT_EQ(without.speed, (std::vector<double>{0.1}));
  EXPECT_FALSE(without.held_out);
  EXPECT_TRUE(parse_regime_grid("held_out=default", without).held_out);
}

TEST(RegimeGrid, BadGridsNameTheAxisAndTheValue) {
  EXPECT_EQ(grid_error(""), "'regime': the grid is empty (give default, full or AXIS=V1,V2;...)");
  EXPECT_EQ(grid_error("spin"),
            "'regime': expected AXIS=V1,V2,... for each axis, separated by ';' (or default, full), got 'spin'");
  EXPECT_EQ(grid_error("mass=1"),
            "'regime': unknown axis 'mass' (known: inertia, spin, roughness, t_end, bowl, speed; and held_out)");
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
  EXPECT_EQ(grid_error("speed=0"), "'regime': speed: 0 is not > 0");
  EXPECT_EQ(grid_error("speed=-0.5"), "'regime': speed: -0.5 is not > 0");
  for (const char* bad : {"0", "-1", "5", "7.5"})
    EXPECT_EQ(grid_error(std::string("bowl=") + bad),
              std::string("'regime': bowl: a = ") + bad +
                  " is outside (0, 5) (the bowl's curvature 2a must be > 0 and the ball of radius 0.1 m must fit "
                  "its bottom, r 2a < 1)");
  EXPECT_EQ(grid_error("held_out=some"), "'regime': held_out: expected none or default, got 'some'");
  EXPECT_EQ(grid_error("held_out=none;held_out=default"), "'regime': held_out is given twice");
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
  ASSERT_EQ(scenes.size(), cells.size() + 9u);  // then the held-out scenes
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Scene& s = scenes[i];
    EXPECT_EQ(s.name, cells[i].scene);
    EXPECT_EQ(s.t_end, cells[i].t_end);
    EXPECT_EQ(s.start.spin, cells[i].spin);
    EXPECT_NEAR(s.params.at("b") * s.params.at("k"), cells[i].roughness, 1e-15);
    EXPECT_EQ(s.ball.inertia.has_value(), cells[i].inertia != 1.0) << s.name;
    EXPECT_EQ(make_problem(s).model().anisotropic(), cells[i].inertia != 1.0) << s.name;
  }
  EXPECT_EQ(cells.front().scene, "regime-i1-s0.1-r0-t1-a0.1-v0.1");
  EXPECT_EQ(cells.back().scene, "regime-i3-s50-r0.3-t1-a2-v0.5");
}

TEST(RegimeScenes, TheStartRollsRoundTheBowlAtTheCellsSpeed) {
  for (const RegimeCell& c : regime_cells(default_regime_grid())) {
    const Scene s = checked_scene(regime_scene(c));
    EXPECT_EQ(s.params.at("a"), c.bowl);
    ASSERT_TRUE(s.start.horizontal_velocity.has_value()) << s.name;
    EXPECT_EQ(*s.start.horizontal_velocity, Vec2(0.0, c.speed));
    // on the x axis, at the radius of the circle the ball keeps at that
    // speed in the bowl's harmonic bottom: rho Omega = speed
    const double omega = bowl_frequency(2.0 * c.bowl, 0.1, 1.0, 0.004, 9.81);
    EXPECT_EQ(s.start.contact.y(), 0.0);
    EXPECT_NEAR(s.start.contact.x() * omega, c.speed, 1e-15) << s.name;
  }
}

TEST(RegimeScenes, TheBowlFrequencyAndTheStartRatesAgainstClosedForms) {
  // the homogeneous ball in a sphere of radius 1 / kappa: its centre swings
  // on radius 1 / kappa - r, slowed by the rolling to 5/7 of the point mass's
  EXPECT_NEAR(bowl_frequency(4.0, 0.1, 1.0, 0.004, 9.81), std::sqrt(9.81 / (0.25 - 0.1) * 5.0 / 7.0), 1e-12);
  EXPECT_NEAR(bowl_frequency(0.2, 0.1, 2.0, 0.002, 9.81), std::sqrt(9.81 / (5.0 - 0.1) / 1.1), 1e-12);
  EXPECT_EQ(bowl_frequency(0.0, 0.1, 1.0, 0.004, 9.81), 0.0);   // a plane: no bowl
  EXPECT_EQ(bowl_frequency(-1.0, 0.1, 1.0, 0.004, 9.81), 0.0);  // a crest
  // chaplygin-bowl: 2 (x^2 + y^2) at (0.02, 0), f_x = 0.08: kappa1 is the
  // curvature across the slope, f_yy / sqrt(1 + f_x^2), above the one down
  // it, f_xx / (1 + f_x^2)^(3/2); omega0 = N x u0 / r + 3 N, u0 = (0, 0.1, 0)
  const RegimeRates bowl = regime_rates(load_scene("chaplygin-bowl"));
  const double kappa = 4.0 / std::sqrt(1.0 + 0.08 * 0.08);
  EXPECT_NEAR(bowl.bowl_frequency, bowl_frequency(kappa, 0.1, 1.0, 0.004, 9.81), 1e-12);
  EXPECT_NEAR(bowl.omega0, std::sqrt(1.0 + 9.0), 1e-12);
  EXPECT_EQ(regime_rates(load_scene("chaplygin-plane")).bowl_frequency, 0.0);
}

TEST(RegimeScenes, TheHeldOutScenesRunBesideTheGridUnlessLeftOut) {
  const RegimeGrid grid =
      parse_regime_grid("inertia=3;spin=5;roughness=0;t_end=1;bowl=0.5;speed=0.1", default_regime_grid());
  const std::vector<Scene> scenes = regime_scenes(grid);
  std::vector<std::string> names;
  for (const Scene& s : scenes) names.push_back(s.name);
  std::vector<std::string> expected = {"regime-i3-s5-r0-t1-a0.5-v0.1"};
  for (const RegimeCell& c : regime_held_out_cells()) expected.push_back(c.scene);
  for (const char* shipped : {"chaplygin-bowl", "chaplygin-bumpy-long", "chaplygin-plane", "chaplygin-valley"})
    expected.push_back(shipped);
  EXPECT_EQ(names, expected);
  // off the grid: bowl and speed off every value of the default and full grids
  auto on = [](const std::vector<double>& axis, double v) {
    return std::find(axis.begin(), axis.end(), v) != axis.end();
  };
  for (const RegimeGrid& g : {default_regime_grid(), full_regime_grid()})
    for (const RegimeCell& c : regime_held_out_cells()) {
      EXPECT_EQ(c.scene.rfind("regime-offgrid-i", 0), 0u) << c.scene;
      EXPECT_FALSE(on(g.bowl, c.bowl) || on(g.speed, c.speed)) << c.scene;
    }
  const json section = regime_json(grid, scenes);
  ASSERT_EQ(section.at("held_out").size(), 9u);
  EXPECT_EQ(section.at("held_out")[0].at("kind"), "off-grid");
  EXPECT_EQ(section.at("held_out")[5].at("scene"), "chaplygin-bowl");
  EXPECT_EQ(section.at("held_out")[5].at("kind"), "shipped");
  EXPECT_EQ(section.at("held_out")[7].at("bowl_frequency"), 0.0);  // chaplygin-plane
  EXPECT_EQ(section.at("axes").at("held_out"), true);

  RegimeGrid without = grid;
  without.held_out = false;
  EXPECT_EQ(regime_scenes(without).size(), 1u);
  EXPECT_TRUE(regime_json(without, scenes).at("held_out").empty());
}

TEST(RegimeScenes, ACellTheSceneCheckRefusesIsAnErrorNamingIt) {
  // bumps of slope 100: the start sits on a crest curved so sharply that
  // gravity cannot hold the rolling ball to it
  try {
    regime_scenes(parse_regime_grid("inertia=1;spin=5;roughness=100;t_end=1;bowl=0.1;speed=0.5;held_out=none",
                                    default_regime_grid()));
    FAIL() << "a scene the ball does not fit was generated";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(
                  "'regime': the cell inertia 1, spin 5 rad/s, roughness 100, t_end 1, bowl "
                  "0.1, speed 0.5 m/s makes no valid scene: 'start': the ball leaves the surface at once: the normal "
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
  ASSERT_EQ(scenes.size(), 72u + 5u + 4u);  // the grid, then the held-out scenes
  EXPECT_EQ(scenes[5].scene.name, regime_cells(*spec.regime)[5].scene);
}

// Issue 31: the regime map's pairs differ only in the geometry, so every Lie
// method of the preset with a tableau has its geometry twin there: a flat
// method of the same tableau and adaptivity, the suite's own (a library's
// has its own norm and controller), with the same controller
// (analysis/pairs.py, geometry_twin).
TEST(RegimePreset, EveryLieMethodWithATableauHasItsGeometryTwin) {
  const SweepSpec spec = preset("regime");
  std::map<std::string, const MethodInfo*> info;
  for (const auto& m : registry()) info[m->info().name] = &m->info();
  std::vector<std::string> paired;
  for (const std::string& name : spec.integrators) {
    ASSERT_EQ(info.count(name), 1u) << name;
    const MethodInfo& lie = *info.at(name);
    if (!lie.on_group || lie.tableau.empty()) continue;
    const bool twin = std::any_of(spec.integrators.begin(), spec.integrators.end(), [&](const std::string& f) {
      const MethodInfo& flat = *info.at(f);
      return !flat.on_group && flat.tableau == lie.tableau && flat.adaptive == lie.adaptive &&
             flat.controller == lie.controller && flat.family != "odeint" && flat.family != "gsl";
    });
    EXPECT_TRUE(twin) << name << " has no geometry twin in the regime preset";
    paired.push_back(name);
  }
  EXPECT_EQ(paired, (std::vector<std::string>{"rkmk4", "rkmk-dp54-adaptive", "rkmk-f78-adaptive"}));
}

// A small grid through the command line: the report's regime section, and
// two shards that merge into it.
TEST(RegimeCli, TheReportRecordsTheGridAndShardsMergeIntoIt) {
  const std::string common =
      "run --regime 'inertia=1,3;spin=5;roughness=0.3;t_end=0.5;bowl=0.1;speed=0.5;held_out=none' --integrators "
      "rk4,rkmk4 --h 2^-3..2^-5 "
      "--repeats 1 --out ";
  const auto whole = testing::cli_temp_file("regime-whole.json");
  testing::CliOutcome o = testing::run_rollbench(common + whole.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const json report = read_report(whole.string());
  EXPECT_EQ(report.at("preset"), "regime");
  const json& cells = report.at("regime").at("cells");
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].at("scene"), "regime-i1-s5-r0.3-t0.5-a0.1-v0.5");
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
      "run --regime 'inertia=1,2;spin=5;roughness=0.3;t_end=0.5;bowl=0.1;speed=0.5;held_out=none' --integrators "
      "rk4,rkmk4 --h 2^-3..2^-5 "
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
  const std::vector<Scene> scenes = regime_scenes(parse_regime_grid(
      "inertia=1;spin=5;roughness=0.1;t_end=1e6;bowl=2;speed=0.1;held_out=none", default_regime_grid()));
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_NE(scenes[0].name.find("1e06"), std::string::npos) << scenes[0].name;
  EXPECT_EQ(scenes[0].name.find('+'), std::string::npos) << scenes[0].name;
}

}  // namespace
}  // namespace rb

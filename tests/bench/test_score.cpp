// rollbench score (bench/lib/score.hpp): a trajectory CSV from any program
// measured against the suite's reference at the suite's output times. A CSV
// written from a run reproduces that run's own error, error_max and drift;
// bad CSVs are refused naming the file, the line and the column.
#include <gtest/gtest.h>

#include <sstream>

#include "bench/lib/report.hpp"
#include "bench/lib/score.hpp"
#include "bench/lib/trajectory_csv.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

// The CSV `rollbench trajectory --dt-out 0.25` (or dt_out) writes for (scene, method, h).
std::string trajectory_csv(const std::string& scene, const std::string& method, double h, double t_end,
                           double dt_out = 0.25) {
  SweepSpec spec;
  spec.scenes = {scene};
  spec.t_end = t_end;
  const std::vector<SweepScene> scenes = prepare_scenes(spec, false);
  RunOptions o;
  o.h = h;
  o.t_end = scenes[0].problem.t_end();
  o.output_times = equally_spaced_outputs(dt_out, o.t_end);
  std::ostringstream out;
  write_trajectory_csv(out, scenes[0].problem, find_integrator(method).integrate(scenes[0].problem, o).output);
  return out.str();
}

nlohmann::json score_of(const std::string& scene, const std::string& csv, double t_end = 2.0) {
  std::istringstream in(csv);
  ScoreOptions options;
  options.t_end = t_end;
  return score_trajectory(scene, in, "t.csv", options);
}

std::string refusal(const std::string& scene, const std::string& csv) {
  try {
    score_of(scene, csv);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

void expect_close(const nlohmann::json& a, const nlohmann::json& b, const std::string& what) {
  if (b.is_null()) {
    EXPECT_TRUE(a.is_null()) << what << ": " << a;
    return;
  }
  ASSERT_TRUE(a.is_number()) << what << ": " << a;
  // the CSV holds omega, the state the momentum: one rounding apart
  EXPECT_NEAR(a.get<double>(), b.get<double>(), 1e-9 * std::abs(b.get<double>()) + 1e-15) << what;
}

TEST(Score, ACsvOfARunReproducesTheReportsErrorAndDrift) {
  // an exact reference (bowl-planar) and a computed one where R feeds back
  // (chaplygin-valley); fixed steps, whose grid run takes the timed run's steps
  for (const auto& [scene, method, h] :
       {std::tuple{"bowl-planar", "rk4", 1.0 / 32.0}, std::tuple{"chaplygin-valley", "midpoint", 1.0 / 64.0}}) {
    SweepSpec spec;
    spec.scenes = {scene};
    spec.t_end = 2.0;
    const std::vector<SweepScene> scenes = prepare_scenes(spec);
    const RunRecord record = run_task(scenes[0], {0, 0, method, h, {}, nullptr}, spec.max_steps);
    ASSERT_EQ(record.status, Status::ok);
    const std::string kind = scenes[0].reference.kind;
    const nlohmann::json expected = {{"error", errors_json(record.error, kind)},
                                     {"error_max", errors_json(record.error_max, kind)}};
    const nlohmann::json score = score_of(scene, trajectory_csv(scene, method, h, 2.0));
    EXPECT_EQ(score["status"], "ok");
    EXPECT_EQ(score["reference"]["kind"], kind);
    for (const char* field : {"error", "error_max"}) {
      for (const char* c : {"contact", "centre", "omega", "rotation", "worst"})
        expect_close(score[field][c], expected[field][c], std::string(scene) + " " + field + "." + c);
      EXPECT_EQ(score[field]["below_floor"], expected[field]["below_floor"]);
      EXPECT_EQ(score[field]["points"], expected[field]["points"]);
      EXPECT_EQ(score[field]["reference"], kind);
    }
    EXPECT_EQ(score["error_max"]["points"], 8);
    EXPECT_GT(score["error"]["worst"].get<double>(), 10 * scenes[0].reference.error);  // a measurement, not the floor
    expect_close(score["drift"]["energy"], record.energy_drift, std::string(scene) + " drift.energy");
    expect_close(score["drift"]["rotation_defect"], record.rotation_drift, std::string(scene) + " drift.rotation");
    expect_close(score["scd"], record.error.scd, std::string(scene) + " scd");
    EXPECT_NE(score["timing"].get<std::string>().find("the user's"), std::string::npos);
  }
}

// The CSV with line `line` (1 = the header) replaced.
std::string with_line(const std::string& csv, std::size_t line, const std::string& text) {
  std::istringstream in(csv);
  std::ostringstream out;
  std::size_t n = 0;
  for (std::string l; std::getline(in, l);) out << (++n == line ? text : l) << '\n';
  return out.str();
}

std::string first_lines(const std::string& csv, std::size_t count) {
  std::istringstream in(csv);
  std::ostringstream out;
  std::string l;
  for (std::size_t n = 0; n < count && std::getline(in, l); ++n) out << l << '\n';
  return out.str();
}

TEST(Score, BadCsvsAreRefusedNamingTheLineAndTheColumn) {
  const std::string csv = trajectory_csv("bowl-planar", "rk4", 1.0 / 32.0, 2.0);
  const std::string header = trajectory_csv_header();
  EXPECT_EQ(refusal("bowl-planar", ""), "'t.csv': line 1: the file is empty; expected the header '" + header + "'");
  std::string renamed = header;
  renamed.replace(renamed.find(",cy,"), 4, ",cY,");
  EXPECT_EQ(refusal("bowl-planar", with_line(csv, 1, renamed)),
            "'t.csv': line 1, column 5 (cy): expected column 'cy', got 'cY'");
  const std::string short_header = header.substr(0, header.find(",energy"));
  EXPECT_EQ(refusal("bowl-planar", with_line(csv, 1, short_header)),
            "'t.csv': line 1, column 19 (energy): missing column 'energy'; expected the header '" + header + "'");
  std::vector<std::string> row_three;  // the fields of line 3 (t = 0.25)
  std::stringstream line_three(first_lines(csv, 3).substr(first_lines(csv, 2).size()));
  for (std::string f; std::getline(line_three, f, ',');) row_three.push_back(f);
  row_three.back().pop_back();  // the newline
  std::string without_last;
  for (std::size_t i = 0; i + 1 < row_three.size(); ++i) without_last += (i ? "," : "") + row_three[i];
  EXPECT_EQ(refusal("bowl-planar", with_line(csv, 3, without_last)),
            "'t.csv': line 3, column 22 (rotation_defect): missing column 'rotation_defect' (the row has 21 of 22)");
  std::string not_a_number = row_three[0] + "," + row_three[1] + "," + row_three[2] + ",abc";
  for (std::size_t i = 4; i < row_three.size(); ++i) not_a_number += "," + row_three[i];
  EXPECT_EQ(refusal("bowl-planar", with_line(csv, 3, not_a_number)),
            "'t.csv': line 3, column 4 (cx): 'abc' is not a number");
  // rows every 0.01 (rollbench trajectory's default spacing) are not the suite's times
  EXPECT_EQ(refusal("bowl-planar", first_lines(trajectory_csv("bowl-planar", "rk4", 0.01, 2.0, 0.01), 4)),
            "'t.csv': line 3, column 1 (t): t = 0.01 is not the next output time of scene 'bowl-planar': expected t = "
            "0.25; the output times are 0.25, 0.5, 0.75, ..., 2 (every 0.25 up to t_end = 2; a row at t = 0 may come "
            "first)");
  // a row after t_end
  const std::string last_row = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  EXPECT_EQ(refusal("bowl-planar", csv + last_row),
            "'t.csv': line 11, column 1 (t): t = 2 comes after t_end = 2, the last output time of scene 'bowl-planar'");
}

TEST(Score, AShortOrNonFiniteTrajectoryIsAResultWithDriftAndNoErrors) {
  const std::string csv = trajectory_csv("bowl-planar", "rk4", 1.0 / 32.0, 2.0);
  const nlohmann::json part = score_of("bowl-planar", first_lines(csv, 6));  // header, t = 0, 0.25 ... 1
  EXPECT_EQ(part["status"], "incomplete");
  EXPECT_EQ(part["message"], "the file ends at t = 1 (line 6), before t_end = 2");
  EXPECT_EQ(part["stop_time"], 1.0);
  EXPECT_TRUE(part["error"]["worst"].is_null());
  EXPECT_TRUE(part["error_max"]["worst"].is_null());
  EXPECT_GT(part["drift"]["energy"].get<double>(), 0.0);

  // the row at t = 0.75 with a non-finite contact point
  std::istringstream in(csv);
  std::string row;
  for (int n = 0; n < 5; ++n) std::getline(in, row);
  const std::size_t x_start = row.find(',') + 1;
  row.replace(x_start, row.find(',', x_start) - x_start, "nan");
  const std::string nan_row = with_line(csv, 5, row);
  const nlohmann::json diverged = score_of("bowl-planar", nan_row);
  EXPECT_EQ(diverged["status"], "diverged");
  EXPECT_EQ(diverged["message"], "a non-finite state at t = 0.75 (line 5)");
  EXPECT_EQ(diverged["stop_time"], 0.5);
  EXPECT_TRUE(diverged["error"]["worst"].is_null());
}

}  // namespace
}  // namespace rb

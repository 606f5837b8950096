#pragma once
// rollbench score: the accuracy and drift of a trajectory made by another
// program (any language), read from a trajectory CSV (docs/formats.md), against
// the suite's reference at the suite's output times, in the report's error,
// error_max and drift fields. The trajectory's timing is the user's.
#include <istream>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/lib/sweep.hpp"

namespace rb {

inline constexpr const char* kScoreSchema = "rollbench.score/1";

struct ScoreOptions {
  double t_end = 0.0;     // 0: the scene's t_end (as `run --preset quick`'s 2 s, give it here)
  double dt_out = 0.0;    // the output grid's spacing; 0: the runner's error grid (error_dt)
  std::string cache_dir;  // reference cache, as `run --cache`; empty: none
};

// Scores the trajectory CSV read from csv (named csv_name in messages) on
// scene (a shipped name or a JSON path). The rows must be the header of
// docs/formats.md and then one row per output time of the runner's grid for the
// scene (every dt_out, or error_dt, up to t_end), optionally preceded by the
// start at t = 0; the errors use the state columns (t, x, y, wx, wy, wz,
// r00 ... r22), from which the suite derives the centre, the momentum and
// the energy itself. Throws InputError naming the file, the line and the
// column for a wrong header, missing columns, a non-number or a time that is
// not the next output time. A row with a non-finite state ends the
// trajectory as "diverged", a file that ends before t_end as "incomplete":
// results, with drift up to there and no errors, as in the report.
nlohmann::json score_trajectory(const std::string& scene, std::istream& csv, const std::string& csv_name,
                                const ScoreOptions& options);

// One trajectory CSV scored on a prepared scene (its grid every spacing):
// status "ok", "incomplete" or "diverged" with the message, the outputs read,
// and the errors and drift in record (error, error_max, energy and rotation
// drift), as score_trajectory measures them. Throws InputError as it does.
struct ScoredTrajectory {
  std::string status = "ok";
  std::string message;
  RunResult run;
  RunRecord record;
};
ScoredTrajectory score_rows(const SweepScene& scene, double spacing, std::istream& csv, const std::string& csv_name);

}  // namespace rb

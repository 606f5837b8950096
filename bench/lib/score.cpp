#include "bench/lib/score.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "bench/lib/report.hpp"
#include "bench/lib/sweep.hpp"
#include "bench/lib/trajectory_csv.hpp"
#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"
#include "problems/utf8.hpp"

namespace rb {

namespace {

using json = nlohmann::json;

// A row of 22 numbers at 17 digits is some 550 bytes: a longer line is no row.
constexpr std::size_t kMaxCsvLineBytes = 64 * 1024;

// columns of the trajectory CSV the state is read from (docs/formats.md order)
constexpr std::size_t kColumnT = 0, kColumnX = 1, kColumnWx = 6, kColumnR00 = 9, kStateColumnsEnd = 18;

std::vector<std::string> split_fields(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();  // a file written on Windows
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string short_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Reads the rows of one CSV and refuses what does not fit, with the place.
class CsvRows {
 public:
  CsvRows(std::istream& in, const std::string& name) : in_(in), name_(name) {
    columns_ = split_fields(trajectory_csv_header());
    const std::vector<std::string>& expected = columns_;
    std::string line;
    if (!read_line(line)) refuse(0, "the file is empty; expected the header " + header_text());
    const std::vector<std::string> got = split_fields(line);
    for (std::size_t c = 0; c < expected.size(); ++c) {
      if (c >= got.size()) refuse(c + 1, "missing column '" + expected[c] + "'; expected the header " + header_text());
      if (got[c] != expected[c])
        refuse(c + 1, "expected column '" + expected[c] + "', got '" + escaped_excerpt(got[c]) + "'");
    }
    if (got.size() > expected.size())
      refuse(expected.size() + 1, "unexpected column '" + escaped_excerpt(got[expected.size()]) + "'");
  }

  // The next row's numbers; false at the end of the file.
  bool next(std::vector<double>& values) {
    std::string line;
    if (!read_line(line)) return false;
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() < columns_.size())
      refuse(fields.size() + 1, "missing column '" + columns_[fields.size()] + "' (the row has " +
                                    std::to_string(fields.size()) + " of " + std::to_string(columns_.size()) + ")");
    if (fields.size() > columns_.size())
      refuse(columns_.size() + 1, "the row has " + std::to_string(fields.size()) + " columns, the header " +
                                      std::to_string(columns_.size()));
    values.resize(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const char* text = fields[c].c_str();
      char* end = nullptr;
      values[c] = std::strtod(text, &end);
      if (fields[c].empty() || end != text + fields[c].size())
        refuse(c + 1, "'" + escaped_excerpt(fields[c]) + "' is not a number");
    }
    return true;
  }

  std::size_t line() const { return line_; }

  // The next line, at most kMaxCsvLineBytes long; false at the end of the file.
  bool read_line(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_;
    if (line.size() > kMaxCsvLineBytes)
      refuse(0, "the line is " + std::to_string(line.size()) + " bytes long; a trajectory's line is at most " +
                    std::to_string(kMaxCsvLineBytes));
    return true;
  }

  // column: 1-based, 0 for the whole line
  [[noreturn]] void refuse(std::size_t column, const std::string& what) const {
    std::string where = "line " + std::to_string(std::max<std::size_t>(line_, 1));
    if (column > 0) {
      where += ", column " + std::to_string(column);
      if (column <= columns_.size()) where += " (" + columns_[column - 1] + ")";
    }
    throw InputError(where + ": " + what, name_);
  }

 private:
  static std::string header_text() {
    std::string text = "'";
    return text.append(trajectory_csv_header()).append("'");
  }

  std::istream& in_;
  const std::string& name_;
  std::vector<std::string> columns_;
  std::size_t line_ = 0;
};

// The grid's times in words: "0.25, 0.5, ..., 2 (every 0.25 up to t_end = 2)".
std::string describe_times(const std::vector<double>& times, double spacing) {
  std::string list;
  for (std::size_t i = 0; i < times.size() && i < 3; ++i) {
    if (i > 0) list += ", ";
    list += short_number(times[i]);
  }
  if (times.size() > 4) list += ", ...";
  if (times.size() > 3) list += ", " + short_number(times.back());
  return list + " (every " + short_number(spacing) + " up to t_end = " + short_number(times.back()) +
         "; a row at t = 0 may come first)";
}

// The flat state of a row: R, alpha and the momentum v whose omega, as the
// suite derives it (T^-1 v), is the row's. Not T(R) omega: for an R off
// SO(3) (a flat method's drift) the closed-form T^-1 of an anisotropic ball
// is not T's inverse, and the suite measures its own runs through T^-1.
FlatState state_of(const Problem& problem, const std::vector<double>& row) {
  const Mat3 R = Eigen::Map<const RowMajorMat3>(row.data() + kColumnR00);
  const Vec2 alpha(row[kColumnX], row[kColumnX + 1]);
  const Vec3 omega(row[kColumnWx], row[kColumnWx + 1], row[kColumnWx + 2]);
  Mat3 omega_of_v;  // v -> omega at (R, alpha), linear in v
  for (int i = 0; i < 3; ++i) omega_of_v.col(i) = problem.model().derived(make_flat(R, Vec3::Unit(i), alpha)).omega;
  return make_flat(R, omega_of_v.partialPivLu().solve(omega), alpha);
}

bool finite_state(const std::vector<double>& row) {
  for (std::size_t c = kColumnX; c < kStateColumnsEnd; ++c)
    if (!std::isfinite(row[c])) return false;
  return true;
}

ScoredTrajectory score_rows(const SweepScene& s, double spacing, CsvRows& rows) {
  ScoredTrajectory scored;
  RunResult& run = scored.run;  // the trajectory as if a method had run: its outputs on the grid
  std::string& status = scored.status;
  std::string& message = scored.message;
  std::vector<double> row;
  bool first = true;
  while (rows.next(row)) {
    const double t = row[kColumnT];
    const bool start = first && t == 0.0;
    first = false;
    if (start) continue;  // the start is the scene's; the drift starts from it
    const std::size_t k = run.output.t.size();
    if (k == s.times.size())
      rows.refuse(kColumnT + 1, "t = " + number_text(t) + " comes after t_end = " + short_number(s.times.back()) +
                                    ", the last output time of scene '" + s.scene.name + "'");
    // a program may print fewer digits than the suite: near enough is the time
    if (!(std::abs(t - s.times[k]) <= 1e-9 * std::max(1.0, s.times[k])))
      rows.refuse(kColumnT + 1, "t = " + number_text(t) + " is not the next output time of scene '" + s.scene.name +
                                    "': expected t = " + short_number(s.times[k]) + "; the output times are " +
                                    describe_times(s.times, spacing));
    if (!finite_state(row)) {
      status = "diverged";
      message = "a non-finite state at t = " + short_number(t) + " (line " + std::to_string(rows.line()) + ")";
      break;
    }
    run.output.push(s.times[k], state_of(s.problem, row));
  }
  run.stop_time = run.output.t.empty() ? 0.0 : run.output.t.back();
  if (status == "ok" && run.output.t.size() < s.times.size()) {
    status = "incomplete";
    message = "the file ends at t = " + short_number(run.stop_time) + " (line " + std::to_string(rows.line()) +
              "), before t_end = " + short_number(s.times.back());
  }
  if (status != "ok") run.status = Status::error;  // not ok: no errors, as for a run that stopped early
  measure_end(s, run, scored.record);
  measure_grid(s, run, scored.record);
  return scored;
}

}  // namespace

ScoredTrajectory score_rows(const SweepScene& scene, double spacing, std::istream& csv, const std::string& csv_name) {
  CsvRows rows(csv, csv_name);
  return score_rows(scene, spacing, rows);
}

json score_trajectory(const std::string& scene_name, std::istream& csv, const std::string& csv_name,
                      const ScoreOptions& options) {
  if (!(options.t_end >= 0.0 && std::isfinite(options.t_end)))
    throw InputError("the end time must be a finite number > 0", "t-end");
  if (!(options.dt_out >= 0.0 && std::isfinite(options.dt_out)))
    throw InputError("the output spacing must be a finite number > 0", "dt-out");
  // the scene, its grid and its reference exactly as `rollbench run` makes them
  SweepSpec spec;
  spec.scenes = {scene_name};
  spec.t_end = options.t_end;
  spec.dt_out = options.dt_out;
  spec.cache_dir = options.cache_dir;
  CsvRows rows(csv, csv_name);  // the header first: a wrong file fails before the reference is computed
  const std::vector<SweepScene> scenes = prepare_scenes(spec);
  const SweepScene& s = scenes.front();
  const double spacing = spec.dt_out > 0.0 ? spec.dt_out : spec.error_dt;
  const ScoredTrajectory scored = score_rows(s, spacing, rows);
  const std::string& status = scored.status;
  const std::string& message = scored.message;
  const RunResult& run = scored.run;
  const RunRecord& r = scored.record;
  const std::string& kind = s.reference.kind;
  return {{"schema", kScoreSchema},
          {"scene", s.scene.name},
          {"trajectory", valid_utf8(csv_name)},  // a path: any bytes
          {"status", status},
          {"message", message},
          {"stop_time", run.stop_time},
          {"output_times", {{"spacing", spacing}, {"t_end", s.times.back()}, {"count", s.times.size()}}},
          {"reference",
           {{"kind", kind},
            {"method", s.reference.method},
            {"cross_check", s.reference.cross_check},
            {"error", s.reference.error},
            {"omega_scale", s.omega_scale},
            {"message", s.reference.message}}},
          {"error", errors_json(r.error, kind)},
          {"error_max", errors_json(r.error_max, kind)},
          {"scd", finite_or_null(r.error.scd)},
          {"drift",
           {{"energy", finite_or_null(r.energy_drift)},
            {"energy_on_group", finite_or_null(r.energy_drift_on_group)},
            {"rotation_defect", finite_or_null(r.rotation_drift)}}},
          {"timing",
           "not measured: the trajectory's timing and cost are the user's; rollbench measured only its "
           "accuracy and drift, at the output times above, against the suite's reference"}};
}

}  // namespace rb

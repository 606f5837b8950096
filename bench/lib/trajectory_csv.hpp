#pragma once
// The trajectory CSV of docs/formats.md: one header row, then one row per output
// time with the state and its derived quantities, 17 significant digits.
#include <ostream>

#include "integrators/integrator.hpp"

namespace rb {

// The header row, without a trailing newline.
const char* trajectory_csv_header();

// Writes the header, a row for the start (t = 0) and a row for every output.
void write_trajectory_csv(std::ostream& out, const Problem& problem, const Trajectory& trajectory);

// Equally spaced output times dt_out, 2 dt_out, ... and t_end (computed as
// k dt_out, not by accumulation). Throws InputError (key "dt-out") when
// dt_out <= 0 or the count would pass max_rows.
std::vector<double> equally_spaced_outputs(double dt_out, double t_end, std::size_t max_rows = 10'000'000);

}  // namespace rb

#include "bench/lib/trajectory_csv.hpp"

#include <cmath>
#include <cstdio>

#include "problems/input_error.hpp"

namespace rb {

const char* trajectory_csv_header() {
  return "t,x,y,cx,cy,cz,wx,wy,wz,r00,r01,r02,r10,r11,r12,r20,r21,r22,energy,normal_force,spin,rotation_defect";
}

namespace {

void write_row(std::ostream& out, const RollingBall& model, double t, const FlatState& y) {
  const Derived d = model.derived(y);
  double values[22];
  int n = 0;
  values[n++] = t;
  values[n++] = y[kOffsetAlpha];
  values[n++] = y[kOffsetAlpha + 1];
  for (int i = 0; i < 3; ++i) values[n++] = d.centre[i];
  for (int i = 0; i < 3; ++i) values[n++] = d.omega[i];
  for (int i = 0; i < 9; ++i) values[n++] = y[kOffsetR + i];
  values[n++] = d.energy;
  values[n++] = d.normal_force;
  values[n++] = d.spin;
  values[n++] = d.rotation_defect;
  char buffer[32];
  for (int i = 0; i < n; ++i) {
    std::snprintf(buffer, sizeof buffer, "%.17g", values[i]);
    if (i > 0) out << ',';
    out << buffer;
  }
  out << '\n';
}

}  // namespace

void write_trajectory_csv(std::ostream& out, const Problem& problem, const Trajectory& trajectory) {
  out << trajectory_csv_header() << '\n';
  write_row(out, problem.model(), 0.0, problem.y0());
  for (std::size_t i = 0; i < trajectory.t.size(); ++i)
    write_row(out, problem.model(), trajectory.t[i], trajectory.y[i]);
}

std::vector<double> equally_spaced_outputs(double dt_out, double t_end, std::size_t max_rows) {
  if (!(dt_out > 0.0) || !std::isfinite(dt_out)) throw InputError("the output spacing must be a number > 0", "dt-out");
  if (!(t_end > 0.0)) throw InputError("the end time must be a number > 0", "t-end");
  const double count = std::floor(t_end / dt_out * (1.0 - 1e-12));
  if (!(count + 1 <= static_cast<double>(max_rows))) {
    // an infinite or astronomical count has no integer to print
    char rows[32];
    if (count < 1e18) std::snprintf(rows, sizeof rows, "%lld", static_cast<long long>(count) + 1);
    else std::snprintf(rows, sizeof rows, "%.3g", count);
    throw InputError(
        "t_end / dt-out asks for " + std::string(rows) + " rows, more than the limit of " + std::to_string(max_rows),
        "dt-out");
  }
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(count) + 1);
  for (std::size_t k = 1; k <= static_cast<std::size_t>(count); ++k) times.push_back(static_cast<double>(k) * dt_out);
  if (times.empty() || times.back() < t_end) times.push_back(t_end);
  return times;
}

}  // namespace rb

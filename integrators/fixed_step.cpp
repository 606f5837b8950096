#include "integrators/fixed_step.hpp"

#include <cstdio>

namespace rb {

std::vector<double> output_times_of(const Problem& problem, const RunOptions& options) {
  const double t_end = t_end_of(problem, options);
  if (!(t_end > 0.0) || !std::isfinite(t_end)) throw InputError("t_end must be a finite number > 0", "t_end");
  std::vector<double> times;
  times.reserve(options.output_times.size() + 1);
  double last = 0.0;
  for (const double t : options.output_times) {
    if (!(t > last) || t > t_end)
      throw InputError("output times must increase within (0, t_end]", "output_times");
    times.push_back(t);
    last = t;
  }
  if (times.empty() || times.back() < t_end) times.push_back(t_end);
  return times;
}

std::string model_stop_reason(const Validity& v, double t) {
  if (v.status != Status::curvature && v.status != Status::lift_off) return v.reason;
  char at[48];
  std::snprintf(at, sizeof at, " at t = %.9g", t);
  return v.reason + at;
}

}  // namespace rb

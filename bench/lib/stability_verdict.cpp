#include "bench/lib/stability_verdict.hpp"

#include <cmath>

namespace rb {

namespace {

// The largest finite value with t in (from, to]; NaN when there is none.
double window_max(const std::vector<double>& t, const std::vector<double>& value, double from, double to) {
  double m = kNaN;
  for (std::size_t i = 0; i < t.size() && i < value.size(); ++i)
    if (t[i] > from && t[i] <= to * (1 + 1e-12) && std::isfinite(value[i]) && !(m >= value[i])) m = value[i];
  return m;
}

double largest(const std::vector<double>& value) {
  double m = kNaN;
  for (const double v : value)
    if (std::isfinite(v) && !(m >= v)) m = v;
  return m;
}

double slope(double from, double to) { return from > 0.0 && to > 0.0 ? std::log2(to / from) : kNaN; }

}  // namespace

GrowthShape growth_shape(const std::vector<double>& t, const std::vector<double>& value, double horizon,
                         const StabilityBounds& b) {
  GrowthShape g;
  const double m1 = window_max(t, value, horizon / 8, horizon / 4);
  const double m2 = window_max(t, value, horizon / 4, horizon / 2);
  const double m3 = window_max(t, value, horizon / 2, horizon);
  g.p_early = slope(m1, m2);
  g.p_late = slope(m2, m3);
  // NaN fails every comparison: an empty window is no evidence of growth
  g.exponential = m3 >= b.growth_floor && g.p_late >= b.growth_exponent && g.p_early >= b.growth_exponent / 3 &&
                  g.p_late >= 1.5 * g.p_early;
  return g;
}

const char* failure_name(StabilityFailure f) {
  switch (f) {
    case StabilityFailure::none: return "none";
    case StabilityFailure::stopped: return "stopped";
    case StabilityFailure::energy: return "energy";
    case StabilityFailure::rotation_defect: return "rotation-defect";
    case StabilityFailure::energy_growth: return "energy-growth";
    case StabilityFailure::defect_growth: return "defect-growth";
  }
  return "none";
}

RungVerdict judge_rung(Status status, const std::vector<double>& t, const std::vector<double>& energy_error,
                       const std::vector<double>& rotation_defect, double horizon, const StabilityBounds& b) {
  RungVerdict v;
  v.energy_error = largest(energy_error);
  v.rotation_defect = largest(rotation_defect);
  v.energy_growth = growth_shape(t, energy_error, horizon, b);
  v.defect_growth = growth_shape(t, rotation_defect, horizon, b);
  // the first that holds, in this order; a non-finite value that the run
  // did not stop for counts as past the bound
  const auto past = [](const std::vector<double>& s, double bound) {
    for (const double x : s)
      if (!(x <= bound)) return true;
    return false;
  };
  if (status != Status::ok) v.failure = StabilityFailure::stopped;
  else if (past(energy_error, b.energy_fraction)) v.failure = StabilityFailure::energy;
  else if (past(rotation_defect, b.rotation_defect)) v.failure = StabilityFailure::rotation_defect;
  else if (v.energy_growth.exponential) v.failure = StabilityFailure::energy_growth;
  else if (v.defect_growth.exponential) v.failure = StabilityFailure::defect_growth;
  return v;
}

}  // namespace rb

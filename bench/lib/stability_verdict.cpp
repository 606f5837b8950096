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

const char* blow_up_name(BlowUp b) {
  switch (b) {
    case BlowUp::none: return "none";
    case BlowUp::stopped: return "stopped";
    case BlowUp::energy: return "energy-blow-up";
    case BlowUp::rotation_defect: return "defect-blow-up";
  }
  return "none";
}

double first_past(const std::vector<double>& t, const std::vector<double>& value, double bound) {
  for (std::size_t i = 0; i < t.size() && i < value.size(); ++i)
    if (!(value[i] <= bound)) return t[i];
  return kNaN;
}

HorizonVerdict judge_horizon(bool stopped_by, const DriftSeries& s, double horizon, double step,
                             const StabilityBounds& b) {
  HorizonVerdict v;
  v.horizon = horizon;
  // the states up to T (the series are in time order)
  std::size_t n = 0;
  while (n < s.t.size() && s.t[n] <= horizon * (1 + 1e-12)) ++n;
  const auto upto = [n](const std::vector<double>& x) {
    return std::vector<double>(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(std::min(n, x.size())));
  };
  const std::vector<double> t = upto(s.t), energy = upto(s.energy), flat = upto(s.energy_flat), defect = upto(s.defect);
  const auto largest = [](const std::vector<double>& x) {
    double m = kNaN;
    for (const double y : x)
      if (std::isfinite(y) && !(m >= y)) m = y;
    return m;
  };
  const auto earliest = [](double a, double c) { return std::isnan(a) || c < a ? c : a; };
  v.energy_error = largest(energy);
  v.energy_error_flat = largest(flat);
  v.rotation_defect = largest(defect);
  v.energy_growth = growth_shape(t, energy, horizon, b);
  v.defect_growth = growth_shape(t, defect, horizon, b);
  const double energy_out = first_past(t, energy, b.energy_fraction);
  const double defect_out = first_past(t, defect, b.rotation_defect);
  v.energy_within = std::isnan(energy_out);
  v.defect_within = std::isnan(defect_out);
  v.crossed_at = earliest(energy_out, defect_out);
  // the failures: the stop (the last state recorded) and the blow-up bounds
  const double energy_blown = first_past(t, energy, b.blow_up_energy);
  const double defect_blown = first_past(t, defect, b.blow_up_defect);
  const double stop = stopped_by && !t.empty() ? t.back() : kNaN;
  v.failed_at = earliest(earliest(stop, energy_blown), defect_blown);
  // the step's own failure: before the first crossing, or within
  // blow_up_steps steps of it (to the first state recorded there: the
  // states are whole steps, not every step)
  double grace = kNaN;
  if (!std::isnan(v.crossed_at)) {
    grace = v.crossed_at + b.blow_up_steps * step;
    for (const double x : t)
      if (x >= grace * (1 - 1e-12)) {
        grace = x;
        break;
      }
  }
  if (!std::isnan(v.failed_at) && (std::isnan(grace) || v.failed_at <= grace)) {
    // the first of them, in this order where two fall on one state
    if (v.failed_at == stop) v.blow_up = BlowUp::stopped;
    else if (v.failed_at == energy_blown) v.blow_up = BlowUp::energy;
    else v.blow_up = BlowUp::rotation_defect;
  }
  return v;
}

}  // namespace rb

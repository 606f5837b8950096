#include "bench/lib/presets.hpp"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string_view>

#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"
#include "problems/whole_number.hpp"

namespace rb {

namespace {

std::vector<double> powers_of_two(int from, int to) {
  std::vector<double> v;
  for (int k = from; k <= to; ++k) v.push_back(std::ldexp(1.0, -k));
  return v;
}

// 2^(-k/4) for k = 4 from .. 4 fine_to, then 2^-k for k = fine_to + 1 ..
// coarse_to: quarter steps where high-order methods converge (large h, a few
// halvings from the reference's floor: order 8 falls 10^2.4 a halving), the
// doubling ladder below, where only low orders are left above the floor and
// each run costs the most.
std::vector<double> step_ladder(int from, int fine_to, int coarse_to) {
  std::vector<double> v;
  for (int k = 4 * from; k <= 4 * fine_to; ++k) v.push_back(std::exp2(-k / 4.0));
  for (int k = fine_to + 1; k <= coarse_to; ++k) v.push_back(std::ldexp(1.0, -k));
  return v;
}

// The horizon study of the presets (docs/usage.md#the-horizon-study): the
// ladder of docs/model.md (a paraboloid of revolution: integrable and
// reversible; the same slightly perturbed: reversible, not integrable;
// gaussian hills: chaotic), each with a homogeneous and an anisotropic
// ball; the bumpy bowl both ways; the Chaplygin ball on the plane, whose
// first integrals it records. The methods: the best fixed-step one of each
// explicit family at order 4 (rk4 and odeint-rk4: one tableau, two codes)
// and at order 1 (euler, exp-euler: flat and on the group), and the
// symmetric implicit methods of orders 2 and 4 on both views (gauss2,
// lie-gauss2; gauss4, lie-gauss2-tj4), the discrete gradient dg2, which
// conserves the energy by construction, and the discrete Lagrange-d'Alembert
// method dla2, symmetric and variational (what variational structure adds).
HorizonSpec horizon_study(long steps) {
  HorizonSpec h;
  h.enabled = true;
  h.scenes = {"paraboloid",     "paraboloid-chaplygin",     "paraboloid-perturbed", "paraboloid-perturbed-chaplygin",
              "gaussian-hills", "gaussian-hills-chaplygin", "bumpy-long",           "chaplygin-bumpy-long",
              "chaplygin-plane"};
  h.integrators = {"euler",          "exp-euler",      "rk4", "odeint-rk4", "gsl-rk4", "rk4-projected",
                   "rk4-quaternion", "rkmk4",          "cf4", "cg4a",       "gauss2",  "lie-gauss2",
                   "gauss4",         "lie-gauss2-tj4", "dg2", "dla2"};
  h.steps = steps;
  return h;
}

}  // namespace

SweepSpec preset(const std::string& name) {
  SweepSpec s;
  s.preset = name;
  if (name == "quick") {
    // CI: a handful of methods, three scenes (one where R feeds back), short runs
    s.scenes = {"valley-sideways", "bowl-planar", "chaplygin-valley"};
    s.integrators = {"euler",
                     "exp-euler",
                     "rk4",
                     "rkmk4",
                     "rkmk4-seminar",
                     "cf4",
                     "cg4a",
                     "odeint-rk4",
                     "gsl-rk4",
                     "odeint-dopri5-adaptive",
                     "gsl-rkf45-adaptive"};
    s.hs = powers_of_two(4, 9);
    s.tols = {1e-4, 1e-6, 1e-8, 1e-10};
    s.t_end = 2.0;
    s.repeats = 2;
    s.repeat_budget_s = 0.2;
  } else if (name == "default") {
    // the README's main job: everything registered on every shipped scene
    // from h = 1: high-order methods reach the floor early, so quarter steps
    // down to 2^-8 give order 8 its points above the floor (on
    // chaplygin-valley rkmk8 converges from h = 2^-3 and meets 10 x the
    // floor near 2^-7)
    s.hs = step_ladder(0, 8, 10);
    s.tols = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11};
    s.repeats = 3;
    s.repeat_budget_s = 0.3;
    s.stability.enabled = true;
    // bounded scenes, one where R feeds back (the Chaplygin ball)
    s.stability.scenes = {"bowl-3d", "bumpy-long", "chaplygin-bumpy-long"};
    s.stability.integrators = {"euler", "exp-euler", "rk4", "rkmk4", "odeint-rk4", "gsl-rk4"};
    s.horizon = horizon_study(1'000'000);
  } else if (name == "full") {
    // a study: finer steps, more repeats, longer drift runs (10^6 steps)
    s.hs = step_ladder(0, 9, 13);
    s.tols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
    s.repeats = 7;
    s.repeat_budget_s = 2.0;
    s.stability.enabled = true;
    s.stability.scenes = {"bowl-3d", "bumpy-long", "chaplygin-bumpy-long"};
    s.stability.integrators = {"euler", "exp-euler", "heun", "rkmk2", "rk4", "rkmk4", "odeint-rk4", "gsl-rk4"};
    s.stability.drift_t_end = 10000.0;
    // 10^7 steps; GSL's Gauss method (implicit, R^T R is a quadratic
    // invariant it keeps) costs about 15 s per 10^5 steps, 25 min per run
    // here: run it with --horizon-integrators where it is wanted
    s.horizon = horizon_study(10'000'000);
  } else if (name == "regime") {
    // the regime map (docs/usage.md, "The regime study"): generated scenes,
    // each Lie method beside its geometry twin (the same tableau, controller
    // and norm: rk4 / rkmk4, rk-dp54-adaptive / rkmk-dp54-adaptive,
    // rk-f78-adaptive / rkmk-f78-adaptive), beside them rk4-projected and
    // cg4a, and odeint's dopri5 and fehlberg78 as library comparisons; steps
    // and tolerances fine enough to read each at 1e-4, 1e-6 and 1e-9
    s.regime = default_regime_grid();
    s.integrators = {"rk4",
                     "rk4-projected",
                     "rkmk4",
                     "cg4a",
                     "rk-dp54-adaptive",
                     "rkmk-dp54-adaptive",
                     "rk-f78-adaptive",
                     "rkmk-f78-adaptive",
                     "odeint-dopri5-adaptive",
                     "odeint-fehlberg78-adaptive"};
    s.hs = powers_of_two(1, 10);
    s.tols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
    s.repeats = 3;
    s.repeat_budget_s = 0.3;
  } else {
    throw InputError("unknown preset '" + name + "' (quick, default, full or regime)", "preset");
  }
  return s;
}

std::vector<double> parse_number_list(const std::string& text, const std::string& key) {
  std::vector<double> values;
  const auto range = text.find("..");
  if (range != std::string::npos) {
    // 2^p..2^q with whole numbers 60 >= p >= q >= -60 (2^0..2^-10): falling,
    // as h is swept; each exponent read strictly (no '+', no spaces)
    const auto exponent = [&](std::size_t from, std::size_t to) -> std::optional<long long> {
      if (text.compare(from, 2, "2^") != 0) return std::nullopt;
      return whole_number_in(std::string_view(text).substr(from + 2, to - from - 2), -60, 60);
    };
    const auto p = exponent(0, range), q = exponent(range + 2, text.size());
    if (!p || !q || *p < *q)
      throw InputError("expected a range like 2^-3..2^-8, got '" + escaped_excerpt(text) + "'", key);
    return powers_of_two(static_cast<int>(-*p), static_cast<int>(-*q));
  }
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v) || v <= 0.0)
      throw InputError("expected positive numbers separated by commas, got '" + item + "'", key);
    values.push_back(v);
  }
  if (values.empty()) throw InputError("the list is empty", key);
  return values;
}

std::vector<double> parse_stability_horizons(const std::string& text, const std::string& key) {
  const std::vector<double> horizons = parse_number_list(text, key);
  for (std::size_t i = 0; i < horizons.size(); ++i) {
    if (horizons[i] > kMaxStabilityHorizon) {
      std::ostringstream out;
      out << "a horizon of at most " << kMaxStabilityHorizon << " s, got " << horizons[i];
      throw InputError(out.str(), key);
    }
    if (i > 0 && !(horizons[i] > horizons[i - 1])) {
      std::ostringstream out;
      out << "the horizons must increase (each run is read at them on its way), got " << horizons[i] << " after "
          << horizons[i - 1];
      throw InputError(out.str(), key);
    }
  }
  return horizons;
}

}  // namespace rb

#pragma once
// Shared by the registry-wide tests: errors of a run against a reference
// state and the observed order of a fixed-step method on one problem.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bench/lib/order_fit.hpp"
#include "integrators/integrator.hpp"
#include "problems/so3.hpp"

namespace rb::testing {

struct EndErrors {
  double contact;   // |alpha - alpha_ref|
  double omega;     // |omega - omega_ref|
  double rotation;  // angle of R_ref^T R after projection
};

inline EndErrors end_errors(const Problem& problem, const FlatState& y, const FlatState& ref) {
  const RollingBall& m = problem.model();
  const Vec3 w =
      m.omega_from_momentum(rotation_of(y), m.normal_at(y[kOffsetAlpha], y[kOffsetAlpha + 1]), Vec3(momentum_of(y)));
  const Vec3 w_ref = m.omega_from_momentum(rotation_of(ref), m.normal_at(ref[kOffsetAlpha], ref[kOffsetAlpha + 1]),
                                           Vec3(momentum_of(ref)));
  return {(contact_of(y) - contact_of(ref)).norm(), (w - w_ref).norm(),
          rotation_angle_between(rotation_of(ref), rotation_of(y))};
}

// A run of method to t_end at fixed step h.
inline RunResult run_at(const Integrator& method, const Problem& problem, double t_end, double h) {
  RunOptions options;
  options.t_end = t_end;
  options.h = h;
  return method.integrate(problem, options);
}

// The rounding floor of method's runs to t_end, measured rather than
// guessed. For n = floor_steps, 2 floor_steps, ... 32 floor_steps, the runs
// of n and n sqrt(2) steps both have truncation errors below rounding (the
// caller picks floor_steps so), so they differ by rounding alone. Rounding
// adds up like a random walk, so each difference is scaled to floor_steps
// steps by sqrt(floor_steps / n), and the largest per component is the floor
// (Ladder::floor, with Ladder::floor_steps = floor_steps): a sample maximum,
// since any one difference may be small by chance.
inline EndErrors rounding_floor(const Integrator& method, const Problem& problem, double t_end, long floor_steps) {
  EndErrors floor{0.0, 0.0, 0.0};
  for (long n = floor_steps; n <= 32 * floor_steps; n *= 2) {
    const double h = t_end / static_cast<double>(n);
    const EndErrors e = end_errors(problem, run_at(method, problem, t_end, h / std::sqrt(2.0)).final_state,
                                   run_at(method, problem, t_end, h).final_state);
    const double scale = std::sqrt(static_cast<double>(floor_steps) / static_cast<double>(n));
    floor = {std::max(floor.contact, scale * e.contact), std::max(floor.omega, scale * e.omega),
             std::max(floor.rotation, scale * e.rotation)};
  }
  return floor;
}

struct Convergence {
  std::vector<double> h, contact, omega, rotation;
  double final_defect = 0.0;  // ||R^T R - I||_F at the end of the finest run
  OrderFit contact_fit, omega_fit, rotation_fit;
};

// The ladder of steps a convergence measurement runs, and the floor below
// which an error is rounding (or the reference's own error), per component.
struct Ladder {
  double h0 = 0.5;      // the first step
  double h_min = 1e-4;  // no step below this
  double ratio = 2.0;   // h falls by this factor
  // errors below 10 * floor are not fitted; a reference good to ~floor / 10
  EndErrors floor{1e-14, 1e-14, 1e-14};
  // > 0: floor is the rounding of a run of this many steps, and a run of n
  // steps has floor * sqrt(n / floor_steps) (rounding adds up like a random
  // walk, so a run of many small steps has more of it than the reference)
  long floor_steps = 0;
  std::size_t points = 3;  // at most this many points per fit
  // the ladder ends at the first run whose contact error is below this
  // (0: below 10 * its floor); a method's solver may have a floor of its own
  double stop = 0.0;
};

// Runs method down the ladder while the contact error stays above 10 * its
// floor (or ladder.stop); runs that fail (large h) are left out. Each run is recorded at the step
// it took, t_end / steps: a ratio such as sqrt(2) does not divide t_end,
// and the driver then takes equal steps a little shorter than h (recording
// h instead makes the local slopes zigzag by +-1.5 for order 8). The order
// is the slope over the smallest steps above the floor (and below 0.1), the
// most asymptotic data there is: high-order pairs such as dopri5 approach
// their order from above and would read high over a wider range.
inline Convergence measure_convergence(const Integrator& method, const Problem& problem, double t_end,
                                       const FlatState& ref, const Ladder& ladder = {}) {
  Convergence c;
  constexpr double kNotFitted = std::numeric_limits<double>::quiet_NaN();
  for (double h = ladder.h0; h >= ladder.h_min; h /= ladder.ratio) {
    const RunResult run = run_at(method, problem, t_end, h);
    if (run.status != Status::ok) continue;
    const EndErrors e = end_errors(problem, run.final_state, ref);
    c.final_defect = rotation_defect(rotation_of(run.final_state));
    const double steps = static_cast<double>(run.cost.steps);
    const double growth =
        ladder.floor_steps > 0 ? std::sqrt(std::max(1.0, steps / static_cast<double>(ladder.floor_steps))) : 1.0;
    // an error on its floor reads as no point at all (fit_order skips NaN)
    const auto above = [&](double error, double floor) { return error > 10.0 * floor * growth ? error : kNotFitted; };
    if (e.contact < 1e-3) {
      c.h.push_back(t_end / steps);
      c.contact.push_back(above(e.contact, ladder.floor.contact));
      c.omega.push_back(above(e.omega, ladder.floor.omega));
      c.rotation.push_back(above(e.rotation, ladder.floor.rotation));
    }
    if (e.contact < (ladder.stop > 0.0 ? ladder.stop : 10.0 * ladder.floor.contact * growth)) break;
  }
  c.contact_fit = fit_order(c.h, c.contact, 0.0, 0.1, ladder.points);
  c.omega_fit = fit_order(c.h, c.omega, 0.0, 0.1, ladder.points);
  c.rotation_fit = fit_order(c.h, c.rotation, 0.0, 0.1, ladder.points);
  return c;
}

}  // namespace rb::testing

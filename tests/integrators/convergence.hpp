#pragma once
// Shared by the registry-wide tests: errors of a run against a reference
// state and the observed order of a fixed-step method on one problem.
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
  const Vec3 w = m.omega_from_momentum(rotation_of(y), m.normal_at(y[kOffsetAlpha], y[kOffsetAlpha + 1]), Vec3(momentum_of(y)));
  const Vec3 w_ref =
      m.omega_from_momentum(rotation_of(ref), m.normal_at(ref[kOffsetAlpha], ref[kOffsetAlpha + 1]), Vec3(momentum_of(ref)));
  return {(contact_of(y) - contact_of(ref)).norm(), (w - w_ref).norm(),
          rotation_angle_between(rotation_of(ref), rotation_of(y))};
}

struct Convergence {
  std::vector<double> h, contact, omega, rotation;
  double final_defect = 0.0;  // ||R^T R - I||_F at the end of the finest run
  OrderFit contact_fit, omega_fit, rotation_fit;
};

// Divides h by ratio (halves it by default) from h0 while the contact error
// stays above 10 * floor and h >= h_min; runs that fail (large h) are left
// out. The reference must be good to ~floor / 10: errors below 10 * floor
// are not fitted (by default 1e-13, for a reference good to ~1e-15). The order is the slope over the
// three smallest steps above that floor (and below 0.1), the most asymptotic
// data there is: high-order pairs such as dopri5 approach their order from
// above and would read high over a wider range.
inline Convergence measure_convergence(const Integrator& method, const Problem& problem, double t_end,
                                       const FlatState& ref, double h0 = 0.5, double h_min = 1e-4,
                                       double floor = 1e-14, double ratio = 2.0) {
  Convergence c;
  for (double h = h0; h >= h_min; h /= ratio) {
    RunOptions options;
    options.t_end = t_end;
    options.h = h;
    const RunResult run = method.integrate(problem, options);
    if (run.status != Status::ok) continue;
    const EndErrors e = end_errors(problem, run.final_state, ref);
    c.final_defect = rotation_defect(rotation_of(run.final_state));
    if (e.contact < 1e-3) {
      c.h.push_back(h);
      c.contact.push_back(e.contact);
      c.omega.push_back(e.omega);
      c.rotation.push_back(e.rotation);
    }
    if (e.contact < 10 * floor) break;
  }
  c.contact_fit = fit_order(c.h, c.contact, floor, 0.1, 3);
  c.omega_fit = fit_order(c.h, c.omega, floor, 0.1, 3);
  c.rotation_fit = fit_order(c.h, c.rotation, floor, 0.1, 3);
  return c;
}

}  // namespace rb::testing

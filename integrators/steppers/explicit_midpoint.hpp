#pragma once
// The worked example of docs/extending.md's "Add your own integrator": one file plus one
// registry line. The explicit midpoint rule on the flat view,
//   y_{n+1} = y_n + h F(y_n + h/2 F(y_n)),
// written by hand (not from a tableau) to show the whole interface.
#include "integrators/fixed_step.hpp"

namespace rb {

class ExplicitMidpoint final : public Integrator {
 public:
  ExplicitMidpoint()
      : Integrator({.name = "midpoint",
                    .family = "rk",
                    .declared_order = 2,
                    .description = "explicit midpoint rule on the flat view (the worked example of docs/extending.md)"}) {}

  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    FlatState k1, k2, mid;  // stage storage lives outside the step: no allocation per step
    auto step = [&](FlatState& y, double /*t*/, double h, Cost& cost) {
      // stage_flat_rhs: each stage's validity margins are noted in cost
      stage_flat_rhs(problem, y.data(), k1.data(), cost);
      mid = y + (0.5 * h) * k1;
      stage_flat_rhs(problem, mid.data(), k2.data(), cost);
      y += h * k2;
      cost.rhs_evals += 2;
    };
    // the shared loop: output times, validity checks, step budget, stop reasons
    return drive_fixed_step(problem, options, step);
  }
};

}  // namespace rb

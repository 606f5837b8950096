#pragma once
// The worked example of docs/extending.md's "Add your own integrator": one
// file plus one registry line, in the shape every shipped fixed-step method
// has (a stepper functor made an integrator by stepped_method). The explicit
// midpoint rule on the flat view,
//   y_{n+1} = y_n + h F(y_n + h/2 F(y_n)),
// written by hand (not from a tableau) to show the whole interface.
#include <memory>
#include <string>

#include "integrators/controllers/controller.hpp"
#include "integrators/steppers/stepped_method.hpp"

namespace rb {

// One step from y to next = y(t + h); the driver (integrators/driver.hpp)
// does the rest: output times, validity checks, step budget, stop reasons.
struct MidpointStep {
  const Problem& problem;
  FlatState k1, k2, mid;  // stage storage lives in the stepper: no allocation per step

  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    // stage_flat_rhs: each stage's validity margins are noted in cost
    stage_flat_rhs(problem, y.data(), k1.data(), cost);
    mid = y + (0.5 * h) * k1;
    stage_flat_rhs(problem, mid.data(), k2.data(), cost);
    next = y + h * k2;
    cost.rhs_evals += 2;
  }
};

// The registry line's shape with no data (the rule is the data):
// explicit_midpoint("midpoint", kConstantController); fixed steps only.
inline std::unique_ptr<Integrator> explicit_midpoint(std::string name, const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "the explicit midpoint rule");
  return stepped_method(
      {.name = std::move(name),
       .family = "rk",
       .declared_order = 2,
       .description = "explicit midpoint rule on the flat view (the worked example of docs/extending.md)"},
      [](const Problem& problem) {
        return MidpointStep{problem, {}, {}, {}};
      });
}

}  // namespace rb

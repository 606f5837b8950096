#pragma once
// Boost.Odeint steppers on the flat view (docs/model.md, "The methods compared"), registered as
// "odeint-...". Odeint's state is a std::array of the 14 flat numbers, so its
// default range_algebra runs with no allocation; the system calls
// Problem::flat_rhs and counts its evaluations in a counter owned by the run.
//
// Fixed-step ones run in drive_fixed_step, adaptive ones in drive_own_controller
// (integrators/driver.hpp, adaptive_loops.hpp). Adding a stepper is one
// OdeintStepper, one row of odeint.cpp's table and one registry line.
#include <array>
#include <memory>
#include <string>

#include "integrators/integrator.hpp"

namespace rb {

// odeint's state and derivative type: y in R^14, laid out as FlatState.
using OdeintState = std::array<double, kFlatSize>;

// The flat view as an odeint system, dxdt = F(x). cost is the run's
// (integrators are shared across threads and keep no state): every call is
// counted and its validity margins noted there (stage_flat_rhs), so that
// the driver sees a stage beyond the model's limits after odeint's step.
struct OdeintSystem {
  const Problem* problem;
  Cost* cost;
  void operator()(const OdeintState& x, OdeintState& dxdt, double /*t*/) const {
    stage_flat_rhs(*problem, x.data(), dxdt.data(), *cost);
    ++cost->rhs_evals;
  }
};

// odeint's steppers: the method data of a registry line. Each runs at fixed
// steps (controller "constant": drive_fixed_step, one do_step a step) and,
// where it estimates its error, with odeint's own controller ("library":
// drive_own_controller, driven by RunOptions::tolerances with odeint's
// error norm, the largest |err_i| / (atol + rtol (|x_i| + h |dxdt_i|)); h is
// the first step tried, 0 chooses one). The declared order is that of the
// solution the stepper advances with: odeint's embedded pairs advance with
// the higher order one (cash_karp54 and dopri5: 5, fehlberg78: 8).
enum class OdeintStepper {
  euler,        // euler: fixed steps only, order 1
  rk4,          // runge_kutta4: fixed steps only, order 4
  cash_karp54,  // runge_kutta_cash_karp54, order 5; adaptive: controlled
  dopri5,       // runge_kutta_dopri5, order 5 (FSAL: 6 evaluations a step); adaptive: dense output
  fehlberg78,   // runge_kutta_fehlberg78, order 8; adaptive: controlled
  // Adams-Bashforth-Moulton (PECE, 2 evaluations a step), started with
  // odeint's runge_kutta4 steps and restarted whenever drive_fixed_step
  // changes h: fixed steps only
  abm4,            // adams_bashforth_moulton<4>, order 4
  abm5,            // adams_bashforth_moulton<5>, order 5
  bulirsch_stoer,  // bulirsch_stoer (controlled extrapolation): adaptive only, declared order 8
};

// The stepper at fixed steps (controller kConstantController) or with
// odeint's own controller (kLibraryController), called name (family
// "odeint"). InputError (key "controller") for any other controller, and for
// a drive the stepper has not (above).
std::unique_ptr<Integrator> odeint_method(OdeintStepper stepper, std::string name, const std::string& controller);

}  // namespace rb

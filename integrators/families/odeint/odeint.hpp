#pragma once
// Boost.Odeint steppers on the flat view (docs/model.md, "The methods compared"), registered as
// "odeint-...". Odeint's state is a std::array of the 14 flat numbers, so its
// default range_algebra runs with no allocation; the system calls
// Problem::flat_rhs and counts its evaluations in a counter owned by the run.
//
// Fixed-step ones run in drive_fixed_step, adaptive ones in drive_own_controller
// (integrators/driver.hpp, adaptive_loops.hpp). Adding a stepper is one factory here and one
// registry line.
#include <array>
#include <memory>

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

// Fixed step, through drive_fixed_step. The declared order is that of the
// solution do_step returns: odeint's embedded pairs advance with the higher
// order one (cash-karp54 and dopri5: 5, fehlberg78: 8).
std::unique_ptr<Integrator> odeint_euler();        // "odeint-euler", order 1
std::unique_ptr<Integrator> odeint_rk4();          // "odeint-rk4", order 4
std::unique_ptr<Integrator> odeint_cash_karp54();  // "odeint-cash-karp54", order 5
std::unique_ptr<Integrator> odeint_dopri5();       // "odeint-dopri5", order 5 (FSAL: 6 evaluations a step)
std::unique_ptr<Integrator> odeint_fehlberg78();   // "odeint-fehlberg78", order 8
// Adams-Bashforth-Moulton (PECE, 2 evaluations a step) with Steps steps,
// started with odeint's runge_kutta4 steps and restarted whenever
// drive_fixed_step changes h: "odeint-abm4" (order 4), "odeint-abm5" (5).
std::unique_ptr<Integrator> odeint_abm4();
std::unique_ptr<Integrator> odeint_abm5();

// Adaptive, driven by RunOptions::rtol and atol (odeint's error norm: the
// largest |err_i| / (atol + rtol (|x_i| + h |dxdt_i|))); h is the first step
// tried, 0 chooses one.
std::unique_ptr<Integrator> odeint_dopri5_adaptive();       // "odeint-dopri5-adaptive": dense output
std::unique_ptr<Integrator> odeint_cash_karp54_adaptive();  // "odeint-cash-karp54-adaptive": controlled
std::unique_ptr<Integrator> odeint_fehlberg78_adaptive();   // "odeint-fehlberg78-adaptive": controlled
std::unique_ptr<Integrator> odeint_bulirsch_stoer();        // "odeint-bulirsch-stoer": controlled

}  // namespace rb

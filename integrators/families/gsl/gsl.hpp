#pragma once
// Adapters for the GSL odeiv2 steppers on the flat view (docs/model.md, "The methods compared"):
// explicit rk2, rk4, rkf45, rkck, rk8pd, msadams and implicit rk1imp, rk2imp,
// rk4imp, bsimp, msbdf, the implicit ones fed the exact Jacobian of F
// (problems/jacobian.hpp).
//
// Two ways to drive a stepper:
// - fixed step (controller "constant"): one gsl_odeiv2_step_apply per
//   step of drive_fixed_step (the shared loop: uniform steps landing on the
//   outputs, per-step checks, step budget). GSL's error estimate is
//   computed but not used.
// - adaptive (controller "library", GSL's own): one gsl_odeiv2_evolve_apply
//   per accepted step with the standard control (rtol, atol on y), t1 = the
//   next output time so the outputs are hit exactly.
//
// Every run allocates its GSL objects once and frees them on every path;
// the counters live in the run, so one instance serves many threads.
#include <memory>
#include <string>
#include <utility>

#include "integrators/integrator.hpp"

namespace rb {

enum class GslDrive { fixed_step, adaptive };

class GslIntegrator final : public Integrator {
 public:
  // stepper: GSL's name ("rk4", "rkf45", "msbdf", ...), the method data of
  // its registry line; name: its registry name ("gsl-rk4", by custom
  // "gsl-rk4-adaptive" for the adaptive drive); controller: "constant" for
  // the fixed-step drive, "library" for the adaptive one (GSL's standard
  // control). Throws InputError (key "integrator") for a stepper GSL does
  // not have, and (key "controller") for any other controller, or for
  // "constant" with a variable-order one (bsimp, msadams, msbdf: adaptive
  // only). Its declared order is that of the solution GSL propagates, which
  // is not always the one gsl_odeiv2_step_order reports: rk2 advances with
  // its 3rd-order member; variable-order methods declare their highest
  // order.
  GslIntegrator(const std::string& stepper, std::string name, const std::string& controller);

  // Fixed step: options.h > 0 is the step; rtol/atol, when given, set the
  // Newton tolerance of the implicit steppers (default 1e-13). Adaptive:
  // rtol, atol >= 0, not both 0; options.h is the first step (0: 1e-3 t_end).
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

 private:
  GslIntegrator(int index, std::string name, const std::string& controller);
  int index_;  // into the stepper table in gsl.cpp
  GslDrive drive_;
};

// The registry's shape of GslIntegrator, gsl_method(stepper, name,
// controller): GSL stays an adapter (its own driver inside integrate), its
// line reads as every other method's.
inline std::unique_ptr<Integrator> gsl_method(const std::string& stepper, std::string name,
                                              const std::string& controller) {
  return std::make_unique<GslIntegrator>(stepper, std::move(name), controller);
}

// GSL's default error handler aborts the process. This switches it off
// (once, thread-safe) so that every GSL error comes back as a status code;
// every GSL entry point of the suite calls it first.
void gsl_errors_off();

}  // namespace rb

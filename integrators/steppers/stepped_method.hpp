#pragma once
// A fixed-step integrator made of parts: its facts (MethodInfo) and a
// fixed-step stepper, run by the one driver with the constant controller.
// Every shipped fixed-step method of the suite is one (the tableau methods,
// the exponential products, the baselines, midpoint); a new way of stepping
// is then one file (the stepper and a factory calling stepped_method) and one
// registry line; see docs/extending.md, "Add your own integrator".
//
// The stepper is a functor in any shape drive_fixed_step takes
// (integrators/driver.hpp), e.g.
//   void operator()(const FlatState& y, FlatState& next, double t, double h,
//                   Cost& cost)  (its stages through stage_flat_rhs / stage_lie_rhs)
// holding (or pointing to) its stage storage, so that the step loop
// allocates nothing. The factory's make is called once per run, in one of
// two forms:
//   make(problem) -> stepper                      the usual one;
//   make(problem, drive) -> drive(stepper)        for a stepper whose type
//       is chosen per run (the tableau steppers unroll their stage loop for
//       the tableau's stage count) or whose storage lives in make's frame.
#include <memory>
#include <type_traits>
#include <utility>

#include "integrators/driver.hpp"

namespace rb {

template <class MakeStepper>
class SteppedMethod final : public Integrator {
 public:
  SteppedMethod(MethodInfo info, MakeStepper make) : Integrator(std::move(info)), make_(std::move(make)) {}
  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    if constexpr (std::is_invocable_v<const MakeStepper&, const Problem&>) {
      auto stepper = make_(problem);
      return drive_fixed_step(problem, options, stepper);
    } else {
      return make_(problem, [&](auto&& stepper) { return drive_fixed_step(problem, options, stepper); });
    }
  }

 private:
  MakeStepper make_;
};

// A fixed-step integrator from its facts (adaptive = false and controller
// "constant" are implied) and a stepper factory.
template <class MakeStepper>
std::unique_ptr<Integrator> stepped_method(MethodInfo info, MakeStepper make) {
  info.adaptive = false;
  return std::make_unique<SteppedMethod<MakeStepper>>(std::move(info), std::move(make));
}

}  // namespace rb

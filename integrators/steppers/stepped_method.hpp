#pragma once
// An integrator made of parts: its facts (MethodInfo) and a fixed-step
// stepper, run by the one driver with the constant controller. A new way of
// stepping is then one file (the stepper and a factory calling
// stepped_method) and one registry line; see docs/extending.md, "Add your own
// integrator".
//
// make(problem) returns the stepper for one run: a functor in any shape
// drive_fixed_step takes (integrators/driver.hpp), e.g.
//   void operator()(const FlatState& y, FlatState& next, double t, double h,
//                   Cost& cost)  (its stages through stage_flat_rhs / stage_lie_rhs)
// holding its stage storage, so that the step loop allocates nothing.
#include <memory>
#include <utility>

#include "integrators/driver.hpp"

namespace rb {

template <class MakeStepper>
class SteppedMethod final : public Integrator {
 public:
  SteppedMethod(MethodInfo info, MakeStepper make) : Integrator(std::move(info)), make_(std::move(make)) {}
  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    auto stepper = make_(problem);
    return drive_fixed_step(problem, options, stepper);
  }

 private:
  MakeStepper make_;
};

// A fixed-step integrator from its facts (adaptive = false and controller
// "constant" are implied) and a stepper factory.
template <class MakeStepper>
std::unique_ptr<Integrator> stepped_method(MethodInfo info, MakeStepper make) {
  return std::make_unique<SteppedMethod<MakeStepper>>(std::move(info), std::move(make));
}

}  // namespace rb

#pragma once
// An integrator made of parts: its facts (MethodInfo) and a fixed-step
// stepper, run by the one driver with the constant controller. A new way of
// stepping is then one file (the stepper and a factory calling
// stepped_method) and one registry line; see README, "Add your own
// integrator".
//
// make(problem) returns the stepper for one run: a functor in any shape
// drive_fixed_step takes (integrators/driver.hpp), e.g.
//   void operator()(const FlatState& y, FlatState& next, double t, double h,
//                   Cost& cost, ModelMargins& margins)
// holding its stage storage, so that the step loop allocates nothing.
#include <memory>
#include <utility>

#include "integrators/driver.hpp"

namespace rb {

template <class MakeStepper>
class SteppedMethod final : public Integrator {
 public:
  SteppedMethod(MethodInfo info, MakeStepper make) : info_(std::move(info)), make_(std::move(make)) {
    if (info_.rotation_order == 0) info_.rotation_order = info_.declared_order;
  }
  std::string name() const override { return info_.name; }
  std::string family() const override { return info_.family; }
  int declared_order() const override { return info_.declared_order; }
  int rotation_order() const override { return info_.rotation_order; }
  bool needs_jacobian() const override { return info_.needs_jacobian; }
  std::string description() const override { return info_.description; }
  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    auto stepper = make_(problem);
    return drive_fixed_step(problem, options, stepper);
  }

 private:
  MethodInfo info_;
  MakeStepper make_;
};

// A fixed-step integrator from its facts (adaptive = false and controller
// "constant" are implied) and a stepper factory.
template <class MakeStepper>
std::unique_ptr<Integrator> stepped_method(MethodInfo info, MakeStepper make) {
  return std::make_unique<SteppedMethod<MakeStepper>>(std::move(info), std::move(make));
}

}  // namespace rb

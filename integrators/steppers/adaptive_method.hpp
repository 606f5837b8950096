#pragma once
// An adaptive integrator made of parts, as SteppedMethod is a fixed-step
// one: its facts (MethodInfo) and an error-estimating stepper (try_step /
// accept, integrators/adaptive_loops.hpp), run by drive_estimating composed
// with a FilterController made for the run: the method's default
// (MethodInfo::controller, "pi" unless given) or the run's
// (RunOptions::controller, `--controller`).
//
// with_stepper(problem, options, tolerances, drive) makes the stepper for one
// run and returns drive(stepper), so that a method may choose its stepper's
// type per run (the Lie pairs: dense output or clamped steps).
#include <memory>
#include <string>
#include <utility>

#include "integrators/adaptive_loops.hpp"

namespace rb {

template <class WithStepper>
class AdaptiveMethod final : public Integrator {
 public:
  // Throws InputError (key "controller") when the method's controller is no filter.
  AdaptiveMethod(MethodInfo info, WithStepper with_stepper)
      : Integrator(adaptive_facts(std::move(info))),
        own_controller_(&filter_controller(this->controller())),
        with_stepper_(std::move(with_stepper)) {}
  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    const ControllerKind* filter = options.controller ? options.controller : own_controller_;
    return with_stepper_(problem, options, options.tolerances, [&](auto& stepper) {
      return drive_estimating(problem, options, declared_order(), stepper,
                              FilterController(*filter, stepper.error_order()));
    });
  }

 private:
  static MethodInfo adaptive_facts(MethodInfo info) {
    info.adaptive = true;
    if (info.controller.empty()) info.controller = "pi";
    return info;
  }
  const ControllerKind* own_controller_;  // the method's filter, looked up once
  WithStepper with_stepper_;
};

// An adaptive integrator from its facts (adaptive = true is implied, the
// controller defaults to "pi") and a stepper maker as above.
template <class WithStepper>
std::unique_ptr<Integrator> adaptive_method(MethodInfo info, WithStepper with_stepper) {
  return std::make_unique<AdaptiveMethod<WithStepper>>(std::move(info), std::move(with_stepper));
}

}  // namespace rb

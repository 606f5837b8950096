#pragma once
// The step h of a run (docs/design.md, "Options are typed where they
// enter"): a value checked where the number enters (the CLI, a sweep's step
// list, a test) and carried by RunOptions, as Tolerances is; an integrator
// reads it and checks only what depends on the method (fixed_step()).
#include <cmath>

#include "problems/input_error.hpp"

namespace rb {

// h >= 0 and finite. 0 is "none given": an adaptive method then chooses its
// first step, a fixed-step one refuses it (fixed_step()).
class StepSize {
 public:
  StepSize() = default;
  // Checked: throws InputError (key "h") unless finite and >= 0. Implicit,
  // so that options.h = 0.01 reads as the number it is.
  StepSize(double h) : h_(h) {  // NOLINT(google-explicit-constructor)
    if (!std::isfinite(h) || h < 0.0)
      throw InputError("the step h must be a finite number >= 0 (0: an adaptive method chooses its first step)", "h");
  }
  operator double() const { return h_; }  // NOLINT(google-explicit-constructor)

  // The step of a fixed-step method: throws InputError (key "h") when none
  // was given (h = 0).
  double fixed_step() const {
    if (!(h_ > 0.0)) throw InputError("a fixed-step method needs a step h > 0", "h");
    return h_;
  }

 private:
  double h_ = 0.0;
};

}  // namespace rb

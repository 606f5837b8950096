#pragma once
// The tolerances of an adaptive run (docs/design.md, "Options are typed
// where they enter"): a value checked once, where the numbers enter (the
// CLI, a sweep's tolerance list), and carried by RunOptions; an integrator
// reads it and checks nothing.
#include <cmath>

#include "problems/input_error.hpp"

namespace rb {

// As the error norm of a controller uses them: a component's error is
// measured against atol + rtol * |y_i|.
class Tolerances {
 public:
  // None: what a fixed-step run carries; an adaptive run refuses it
  // (tolerances_of, integrators/driver.hpp).
  Tolerances() = default;
  // Checked: each finite and >= 0, not both 0. Throws InputError naming
  // "rtol" or "atol".
  Tolerances(double rtol, double atol) : rtol_(rtol), atol_(atol) {
    auto check = [](double value, const char* key) {
      if (!std::isfinite(value) || value < 0.0)
        throw InputError("an adaptive method needs a finite tolerance >= 0", key);
    };
    check(rtol, "rtol");
    check(atol, "atol");
    if (rtol == 0.0 && atol == 0.0) throw InputError("an adaptive method needs rtol > 0 or atol > 0", "rtol");
  }

  double rtol() const { return rtol_; }
  double atol() const { return atol_; }
  // whether the tolerances were given (a default-constructed value is none)
  bool given() const { return rtol_ > 0.0 || atol_ > 0.0; }

 private:
  double rtol_ = 0.0;
  double atol_ = 0.0;
};

}  // namespace rb

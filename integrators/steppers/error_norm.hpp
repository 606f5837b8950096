#pragma once
// The error norm of every embedded pair the suite's controllers drive (the
// flat, Lie and exponential-product pairs): Hairer's root mean square, each
// component of the error estimate measured against its own scale,
//   err = sqrt(1/n sum_i (e_i / scale_i)^2),
// a value component's scale atol + rtol max(|y_i|, |y_new_i|) (the step's
// start and end), a rotation's (rad) atol + rtol. err <= 1 meets the
// tolerance (integrators/controllers/).
#include <cmath>

#include "integrators/driver.hpp"

namespace rb {

// atol + rtol max(|y_i|, |y_new_i|), per component
template <class V>
V value_scale(const Tolerances& tol, const V& y, const V& y_new) {
  return (tol.atol() + tol.rtol() * y.cwiseAbs().cwiseMax(y_new.cwiseAbs()).array()).matrix();
}

// the scale of a rotation error (rad): the size of a rotation is about 1
inline double rotation_scale(const Tolerances& tol) { return tol.atol() + tol.rtol(); }

// sum_i (e_i / scale_i)^2
template <class V>
double scaled_squares(const V& e, const V& scale) {
  return (e.array() / scale.array()).square().sum();
}

// The root mean square of n components from their scaled squares.
inline double rms_error(double squares, int n) { return std::sqrt(squares / static_cast<double>(n)); }

// Hairer's stretched combination of two estimates' scaled squares (DP853:
// e2 of the order-5 estimate, e3 of the order-3 one), as in DOP853.
inline double stretched_rms_error(double e2, double e3, int n) {
  if (e2 == 0.0 && e3 == 0.0) return 0.0;
  return e2 / std::sqrt((e2 + 0.01 * e3) * static_cast<double>(n));
}

}  // namespace rb

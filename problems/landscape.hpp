#pragma once
// The landscape z = f(x, y) the ball rolls on: f, grad f and Hess f at a
// contact point (x, y), from a formula (docs/formats.md, "Formula language").
// Lengths are in the scene's units; x, y and z are world coordinates.
#include <map>
#include <string>
#include <string_view>

#include "problems/formula.hpp"

namespace rb {

class Landscape {
 public:
  // The flat landscape z = 0.
  Landscape() = default;
  explicit Landscape(Formula formula) : formula_(std::move(formula)) {}

  // Compiles the formula, to native code where it can (formula_native.hpp,
  // else the tape); throws InputError with the column of the problem (place
  // it under the scene key with InputError::under("landscape")).
  static Landscape parse(std::string_view text, const std::map<std::string, double>& params = {}) {
    Formula formula = Formula::parse(text, params);
    formula.compile_native();
    return Landscape(std::move(formula));
  }

  // f, (fx, fy) and (fxx, fxy, fyy) at (x, y); T is double or an AD number.
  // Non-finite where the formula is undefined; never throws.
  template <class T>
  [[gnu::always_inline]] Jet2<T> at(const T& x, const T& y) const {
    return formula_.eval(x, y);
  }

  // (fx, fy) and (fxx, fxy, fyy) at (x, y), f left NaN: what the equations
  // of motion need, a little cheaper than at().
  template <class T>
  [[gnu::always_inline]] Jet2<T> slopes(const T& x, const T& y) const {
    return formula_.slopes(x, y);
  }

  // f(x, y) alone.
  double height(double x, double y) const { return formula_.value(x, y); }

  const std::string& text() const { return formula_.text(); }
  const Formula& formula() const { return formula_; }

 private:
  Formula formula_;
};

}  // namespace rb

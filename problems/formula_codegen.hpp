#pragma once
// A formula's lowered tape (formula_tape.hpp) as C source, for the native
// landscape (formula_native.hpp). The source comes only from the tape's op
// codes, register numbers and constants (written as their IEEE bits), never
// from the formula's text, so no formula can put code into it. It runs the
// tape's double operations in the tape's order; compiled without
// contraction (-ffp-contract=off) it gives the tape's bits.
#include <string>

#include "problems/formula_tape.hpp"

namespace rb {

// Bumped whenever the generated code changes: part of the cache key.
inline constexpr int kFormulaCodegenVersion = 1;

// Defines `void rb_formula_full(double x, double y, double out[6])` and
// `rb_formula_slopes` (f, fx, fy, fxx, fxy, fyy into out; slopes leaves f
// NaN), each running one of the tape's programs.
std::string formula_c_source(const FormulaTape& tape);

}  // namespace rb

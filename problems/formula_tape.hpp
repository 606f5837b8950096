#pragma once
// A formula's Jet2<double> evaluation lowered to straight-line scalar code
// (formula.cpp builds it from the stack program of formula.hpp): one scalar
// instruction per double operation of the jet ops, on a small register file,
// with the parts known at compile time (the zero Hessian of x*pi, the zero
// y-derivatives of a function of x) costing nothing. It runs the same double
// operations in the same order as the stack machine, so its results are the
// same bits, except that a structurally zero derivative stays 0 where the
// stack machine multiplied inf by 0 (NaN) and that some zero derivatives may
// differ in sign.
//
// Why: the stack machine moves whole jets (six doubles) through memory for
// every op and does the full jet arithmetic; on the valley scene this tape
// takes the formula from about 45 % to about 15 % of a right-hand side.
#include <math.h>  // sincos (glibc, _GNU_SOURCE), for clang

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "problems/jet.hpp"

namespace rb {

// One instruction of a FormulaTape: r[dst] = code(r[a], r[b] or c). Every op
// reads a register a; sincos writes sin to dst and cos to b, cossin the
// other way round.
enum class TapeCode : std::uint8_t {
  add,
  sub,
  mul,
  div,
  pow,
  atan2,
  hypot,  // r[a] op r[b]
  add_c,
  mul_c,
  div_c,
  pow_c,
  atan2_c,
  hypot_c,  // r[a] op c
  rsub_c,
  rdiv_c,
  rpow_c,
  ratan2_c,
  rhypot_c,  // c op r[a]
  neg,
  sin,
  cos,
  sincos,
  cossin,
  tan,
  asin,
  acos,
  atan,
  sinh,
  cosh,
  tanh,
  exp,
  log,
  sqrt,
};

struct TapeOp {
  TapeCode code;
  std::uint8_t dst = 0, a = 0, b = 0;
  // a is the previous op's result: taken from a machine register instead of
  // r[a], which saves a store-to-load round trip on the dependency chain
  bool chained = false;
  double c = 0.0;
};

struct TapeNode;

// One straight-line program: x in r[0], y in r[1], the ops in order, then
// the six parts gathered from registers, the last result or constants.
class TapeProgram {
 public:
  static constexpr std::size_t kMaxRegisters = 128;

  std::size_t size() const { return ops_.size(); }

  // What run() executes, for the native code generator (formula_codegen.cpp).
  static constexpr int kConstant = -1;  // output(): the part is constant_parts()'s
  static constexpr int kLast = -2;      // output(): the part is the last op's result
  const std::vector<TapeOp>& ops() const { return ops_; }
  int output(std::size_t part) const { return out_[part]; }
  const Jet2<double>& constant_parts() const { return constant_parts_; }
  int first_input() const { return first_input_; }

  // Inlined into its callers: Formula::run_tape (itself out of line, for
  // eval and slopes) and the native code's check against the tape.
  [[gnu::always_inline]] Jet2<double> run(double x, double y) const {
    std::array<double, kMaxRegisters> r;
    r[0] = x;
    r[1] = y;
    double last = first_input_ == 0 ? x : y;  // the previous op's result
    for (const TapeOp& op : ops_) {
      const double a = op.chained ? last : r[op.a];
      double d;
      switch (op.code) {
        case TapeCode::add: d = a + r[op.b]; break;
        case TapeCode::sub: d = a - r[op.b]; break;
        case TapeCode::mul: d = a * r[op.b]; break;
        case TapeCode::div: d = a / r[op.b]; break;
        case TapeCode::pow: d = std::pow(a, r[op.b]); break;
        case TapeCode::atan2: d = std::atan2(a, r[op.b]); break;
        case TapeCode::hypot: d = std::hypot(a, r[op.b]); break;
        case TapeCode::add_c: d = a + op.c; break;
        case TapeCode::mul_c: d = a * op.c; break;
        case TapeCode::div_c: d = a / op.c; break;
        case TapeCode::pow_c: d = std::pow(a, op.c); break;
        case TapeCode::atan2_c: d = std::atan2(a, op.c); break;
        case TapeCode::hypot_c: d = std::hypot(a, op.c); break;
        case TapeCode::rsub_c: d = op.c - a; break;
        case TapeCode::rdiv_c: d = op.c / a; break;
        case TapeCode::rpow_c: d = std::pow(op.c, a); break;
        case TapeCode::ratan2_c: d = std::atan2(op.c, a); break;
        case TapeCode::rhypot_c: d = std::hypot(op.c, a); break;
        case TapeCode::neg: d = -a; break;
        case TapeCode::sin: d = std::sin(a); break;
        case TapeCode::cos: d = std::cos(a); break;
        // one libm call for both, which gives the bits of sin and of cos (as
        // one case: GCC splits a sincos whose results go to swapped places)
        case TapeCode::sincos:
        case TapeCode::cossin: {
          double s, c;
#if defined(__clang__)
          ::sincos(a, &s, &c);  // glibc's (clang has no __builtin_sincos)
#else
          __builtin_sincos(a, &s, &c);
#endif
          const bool cos_first = op.code == TapeCode::cossin;
          d = cos_first ? c : s;
          r[op.b] = cos_first ? s : c;
          break;
        }
        case TapeCode::tan: d = std::tan(a); break;
        case TapeCode::asin: d = std::asin(a); break;
        case TapeCode::acos: d = std::acos(a); break;
        case TapeCode::atan: d = std::atan(a); break;
        case TapeCode::sinh: d = std::sinh(a); break;
        case TapeCode::cosh: d = std::cosh(a); break;
        case TapeCode::tanh: d = std::tanh(a); break;
        case TapeCode::exp: d = std::exp(a); break;
        case TapeCode::log: d = std::log(a); break;
        case TapeCode::sqrt: d = std::sqrt(a); break;
        // the lowering writes no other code: no range check before the jump
        default: __builtin_unreachable();
      }
      r[op.dst] = d;
      last = d;
    }
    // each part: the last result, a register, or the constant it is known to be
    const auto part = [&](int src, double constant) {
      return src >= 0 ? r[static_cast<std::size_t>(src)] : src == kLast ? last : constant;
    };
    const Jet2<double>& c = constant_parts_;
    return {part(out_[0], c.f),   part(out_[1], c.fx),  part(out_[2], c.fy),
            part(out_[3], c.fxx), part(out_[4], c.fxy), part(out_[5], c.fyy)};
  }

 private:
  friend std::optional<TapeProgram> build_tape(const std::vector<TapeNode>& nodes, const std::array<int, 6>& outputs,
                                               const Jet2<double>& constants);
  std::vector<TapeOp> ops_;
  std::array<int, 6> out_{};      // where f, fx, fy, fxx, fxy, fyy are: a register, kConstant or kLast
  std::uint8_t first_input_ = 0;  // the input (0: x, 1: y) the first op reads
  Jet2<double> constant_parts_{};
};

// An instruction as the lowering records it, before scheduling: SSA values,
// 0 is x, 1 is y, node i defines value i + 2; b is -1 where unused.
struct TapeNode {
  TapeCode code;
  int a, b;
  double c;
};

// The program that computes `outputs` (the values of f, fx, fy, fxx, fxy,
// fyy, -1 for a part that is the constant in `constants`) from the nodes:
// live nodes only, ordered so that values pass on in a machine register,
// sin and cos of one argument in one call, registers reused. nullopt when it
// needs more than kMaxRegisters (formula_tape.cpp).
std::optional<TapeProgram> build_tape(const std::vector<TapeNode>& nodes, const std::array<int, 6>& outputs,
                                      const Jet2<double>& constants);

// The lowered formula: `full` gives every part, `slopes` all but f (NaN),
// for the equations of motion, which do not need the height.
struct FormulaTape {
  bool usable() const { return usable_; }
  TapeProgram full, slopes;
  bool usable_ = false;  // false: the formula is too long or deep to lower
};

}  // namespace rb

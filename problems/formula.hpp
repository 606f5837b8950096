#pragma once
// A landscape formula z = f(x, y) (docs/formats.md, "Formula language") compiled
// once to a flat program for a stack machine, then evaluated many times:
// as a plain double, or as a Jet2 with exact gradient and Hessian.
//
// The program has no pointers and no virtual calls: a switch over an op code
// per instruction, on a fixed-size stack array. Constant sub-expressions
// (numbers, pi, e, params) are folded at compile time, and a constant operand
// of a binary op becomes an immediate of that op.
//
// For Jet2<double>, the step loop's case, the program is also lowered once to
// a FormulaTape (formula_tape.hpp), straight-line scalar code that runs the
// jet ops' own double operations, minus those whose result is known.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "problems/formula_native.hpp"
#include "problems/formula_tape.hpp"
#include "problems/input_error.hpp"
#include "problems/jet.hpp"

namespace rb {

enum class OpCode : std::uint8_t {
  // push a constant (c), x or y
  push_const,
  push_x,
  push_y,
  // pop b, pop a, push a op b
  add,
  sub,
  mul,
  div,
  pow,
  atan2,
  hypot,
  // replace the top u: -u, u + c, c - u, u * c, u / c, c / u,
  // u^c (real c), u^n (integer n), c^u
  neg,
  add_const,
  rsub_const,
  mul_const,
  div_const,
  rdiv_const,
  pow_const,
  pow_int,
  rpow_const,
  // replace the top u by g(u)
  sin,
  cos,
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

struct Op {
  OpCode code;
  int n = 0;       // pow_int: the exponent
  double c = 0.0;  // the constant of push_const and the *_const ops
};

namespace formula_detail {

// u^n exactly as Jet2's powi computes its value.
inline double powi_value(double u, int n) {
  if (n == 0) return 1.0;
  if (n < 0) return 1.0 / jet_detail::ipow(u, static_cast<unsigned>(-n));
  return jet_detail::ipow(u, static_cast<unsigned>(n));
}

// One op on doubles: a is the top (a unary op's operand) or, for a binary
// op, the entry below the top, b the top. Used for constant folding and by
// value(), and mirrors Jet2's value computations operation for operation.
// Always inlined, so its switch merges with the evaluator loop's.
[[gnu::always_inline]] inline double value_op(const Op& op, double a, double b) {
  switch (op.code) {
    case OpCode::push_const: return op.c;
    case OpCode::push_x:
    case OpCode::push_y: break;
    case OpCode::add: return a + b;
    case OpCode::sub: return a - b;
    case OpCode::mul: return a * b;
    case OpCode::div: return a / b;
    case OpCode::pow: return std::pow(a, b);
    case OpCode::atan2: return std::atan2(a, b);
    case OpCode::hypot: return std::hypot(a, b);
    case OpCode::neg: return -a;
    case OpCode::add_const: return a + op.c;
    case OpCode::rsub_const: return op.c - a;
    case OpCode::mul_const: return a * op.c;
    case OpCode::div_const: return a / op.c;
    case OpCode::rdiv_const: return op.c / a;
    case OpCode::pow_const: return std::pow(a, op.c);
    case OpCode::pow_int: return powi_value(a, op.n);
    case OpCode::rpow_const: return std::pow(op.c, a);
    case OpCode::sin: return std::sin(a);
    case OpCode::cos: return std::cos(a);
    case OpCode::tan: return std::tan(a);
    case OpCode::asin: return std::asin(a);
    case OpCode::acos: return std::acos(a);
    case OpCode::atan: return std::atan(a);
    case OpCode::sinh: return std::sinh(a);
    case OpCode::cosh: return std::cosh(a);
    case OpCode::tanh: return std::tanh(a);
    case OpCode::exp: return std::exp(a);
    case OpCode::log: return std::log(a);
    case OpCode::sqrt: return std::sqrt(a);
  }
  return std::nan("");
}

}  // namespace formula_detail

class Formula {
 public:
  // Longest accepted formula text, in characters (bytes).
  static constexpr std::size_t kMaxLength = 65536;
  // Deepest nesting of parentheses, function calls, unary signs and
  // exponents; keeps the recursive-descent parser far from the C stack's end.
  static constexpr int kMaxDepth = 200;
  // Each nesting level holds at most three pending operands (a sum's left
  // side, a product's left side, a power's base or a call's first argument),
  // so this stack always suffices; the compiler checks it anyway.
  static constexpr std::size_t kMaxStack = 3 * (kMaxDepth + 1) + 1;

  // The flat landscape z = 0.
  Formula();

  // Compiles text with the given named constants. Throws InputError with an
  // empty key and the 1-based column of the offending character or token
  // (0 for a bad param, which has no place in the text).
  static Formula parse(std::string_view text, const std::map<std::string, double>& params = {});

  // f, grad f and Hess f at (x, y). T is double or a forward-mode AD number
  // (Eigen::AutoDiffScalar). Outside the formula's domain (sqrt of a negative,
  // log of 0) the parts are simply non-finite; never throws.
  template <class T>
  [[gnu::always_inline]] Jet2<T> eval(const T& x, const T& y) const {
    if constexpr (std::is_same_v<T, double>) {
      if (native_) return run_native(native_.full, x, y);
      if (tape_.usable()) return run_tape(tape_.full, x, y);
    }
    if (max_stack_ <= kSmallStack) return run<T, kSmallStack>(x, y);
    return run<T, kMaxStack>(x, y);
  }

  // grad f and Hess f at (x, y), without f itself (left NaN): what the
  // equations of motion need, a few instructions less.
  template <class T>
  [[gnu::always_inline]] Jet2<T> slopes(const T& x, const T& y) const {
    if constexpr (std::is_same_v<T, double>) {
      double out[6];
      if (native_) [[likely]]
        native_.slopes(x, y, out);
      else slopes_off_native(x, y, out);
      return read_out(out);
    } else {
      Jet2<T> j = eval(x, y);
      j.f = T(std::nan(""));
      return j;
    }
  }

  // f(x, y) alone; bitwise equal to eval(x, y).f for double.
  double value(double x, double y) const {
    if (max_stack_ <= kSmallStack) return run_value<kSmallStack>(x, y);
    return run_value<kMaxStack>(x, y);
  }

  // The text as given to parse.
  const std::string& text() const { return text_; }
  // Number of instructions (shows constant folding).
  std::size_t size() const { return program_.size(); }
  // Deepest stack the program reaches.
  std::size_t stack_depth() const { return max_stack_; }
  const std::vector<Op>& program() const { return program_; }
  // The lowered program eval and slopes run for double (formula_tape.hpp).
  const FormulaTape& tape() const { return tape_; }

  // Switches eval and slopes on doubles from the tape to native code built
  // from it (formula_native.hpp), with the settings from the environment;
  // where that cannot be had, keeps the tape and says why on stderr, once
  // per process. Returns whether native code runs now. Never throws.
  bool compile_native();
  // The same with explicit settings, silent: how it went.
  NativeOutcome compile_native(const NativeSettings& settings);
  bool is_native() const { return static_cast<bool>(native_); }
  // Back to the tape (tests compare the two).
  void drop_native() { native_ = {}; }

 private:
  // Stack for ordinary formulas; a Jet2 of a 14-direction AD number is 720
  // bytes, so the full-size stack is used only when needed.
  static constexpr std::size_t kSmallStack = 16;

  template <class T, std::size_t N>
  Jet2<T> run(const T& x, const T& y) const;
  template <std::size_t N>
  double run_value(double x, double y) const;
  // The six numbers are read one by one (volatile): the compiled code
  // stores them one by one, and a caller that read two at once (GCC pairs
  // fx and fy for the unit normal) waited for the stores to reach the cache
  // instead of taking them from the store queue (docs/performance-history.md,
  // "rkmk4 at the limit").
  [[gnu::always_inline]] static Jet2<double> run_native(NativeFormula::Function fn, double x, double y) {
    double out[6];
    fn(x, y, out);
    return read_out(out);
  }
  [[gnu::always_inline]] static Jet2<double> read_out(const double* out) {
    const volatile double* read = out;
    return {read[0], read[1], read[2], read[3], read[4], read[5]};
  }
  // slopes where no native code runs (the tape, else the interpreter), its
  // six numbers into out as the native code writes them: out of line, and
  // through the same buffer, so that the stages' native path merges with
  // nothing kept in registers (docs/performance-history.md, ninth pass)
  [[gnu::noinline]] void slopes_off_native(double x, double y, double* out) const {
    Jet2<double> j;
    if (tape_.usable()) {
      j = run_tape(tape_.slopes, x, y);
    } else {
      j = eval(x, y);
      j.f = std::nan("");
    }
    out[0] = j.f, out[1] = j.fx, out[2] = j.fy, out[3] = j.fxx, out[4] = j.fxy, out[5] = j.fyy;
  }
  // The tape's interpreter, out of line: inlined into every stage next to
  // the native call (its 1 KB register file, libm calls and jump table),
  // it made the stages of native landscapes slower (docs/performance-history.md,
  // "rkmk4 at the limit", fifth pass).
  [[gnu::noinline]] static Jet2<double> run_tape(const TapeProgram& program, double x, double y) {
    return program.run(x, y);
  }
  // Lowers program_ to tape_ where it fits (formula.cpp).
  void lower_to_tape();

  std::string text_;
  std::vector<Op> program_;
  std::size_t max_stack_ = 0;
  FormulaTape tape_;
  NativeFormula native_;
};

// The formula language's own names: variables, constants, functions and the
// rejected non-smooth functions, from the parser's tables (the one list).
std::vector<std::string_view> formula_reserved_names();

// The one check of a param's name, for Formula::parse and for scenes: throws
// InputError (no key; a scene places it under params.<name>) when name is
// not a name or shadows any reserved name, with one sentence for all of them.
void check_formula_param_name(std::string_view name);

template <class T, std::size_t N>
Jet2<T> Formula::run(const T& x, const T& y) const {
  using J = Jet2<T>;
  std::array<J, N> s;
  std::size_t top = 0;  // number of entries; the compiler proved top <= N
  for (const Op& op : program_) {
    J& u = s[top == 0 ? 0 : top - 1];
    switch (op.code) {
      case OpCode::push_const: s[top++] = J::constant(op.c); break;
      case OpCode::push_x: s[top++] = J::variable_x(x); break;
      case OpCode::push_y: s[top++] = J::variable_y(y); break;
      case OpCode::add:
        --top;
        s[top - 1] = s[top - 1] + s[top];
        break;
      case OpCode::sub:
        --top;
        s[top - 1] = s[top - 1] - s[top];
        break;
      case OpCode::mul:
        --top;
        s[top - 1] = s[top - 1] * s[top];
        break;
      case OpCode::div:
        --top;
        s[top - 1] = s[top - 1] / s[top];
        break;
      case OpCode::pow:
        --top;
        s[top - 1] = pow(s[top - 1], s[top]);
        break;
      case OpCode::atan2:
        --top;
        s[top - 1] = atan2(s[top - 1], s[top]);
        break;
      case OpCode::hypot:
        --top;
        s[top - 1] = hypot(s[top - 1], s[top]);
        break;
      case OpCode::neg: u = -u; break;
      case OpCode::add_const: u = u + op.c; break;
      case OpCode::rsub_const: u = op.c - u; break;
      case OpCode::mul_const: u = u * op.c; break;
      case OpCode::div_const: u = u / op.c; break;
      case OpCode::rdiv_const: u = op.c / u; break;
      case OpCode::pow_const: u = pow(u, op.c); break;
      case OpCode::pow_int: u = powi(u, op.n); break;
      case OpCode::rpow_const: u = pow(op.c, u); break;
      case OpCode::sin: u = sin(u); break;
      case OpCode::cos: u = cos(u); break;
      case OpCode::tan: u = tan(u); break;
      case OpCode::asin: u = asin(u); break;
      case OpCode::acos: u = acos(u); break;
      case OpCode::atan: u = atan(u); break;
      case OpCode::sinh: u = sinh(u); break;
      case OpCode::cosh: u = cosh(u); break;
      case OpCode::tanh: u = tanh(u); break;
      case OpCode::exp: u = exp(u); break;
      case OpCode::log: u = log(u); break;
      case OpCode::sqrt: u = sqrt(u); break;
    }
  }
  return s[0];
}

template <std::size_t N>
double Formula::run_value(double x, double y) const {
  std::array<double, N> s;
  std::size_t top = 0;
  for (const Op& op : program_) {
    switch (op.code) {
      case OpCode::push_const: s[top++] = op.c; break;
      case OpCode::push_x: s[top++] = x; break;
      case OpCode::push_y: s[top++] = y; break;
      case OpCode::add:
      case OpCode::sub:
      case OpCode::mul:
      case OpCode::div:
      case OpCode::pow:
      case OpCode::atan2:
      case OpCode::hypot:
        --top;
        s[top - 1] = formula_detail::value_op(op, s[top - 1], s[top]);
        break;
      default: s[top - 1] = formula_detail::value_op(op, s[top - 1], 0.0);
    }
  }
  return s[0];
}

}  // namespace rb

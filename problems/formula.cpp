// Lowering a formula's stack program to a FormulaTape (formula.hpp): the
// program runs once on Jet2<Sym>, where Sym is a symbolic scalar whose
// arithmetic records scalar instructions instead of computing. The jet ops of
// jet.hpp are thus the single source of the derivative rules, and the tape
// runs exactly their double operations, minus those with a known result:
//   - constant operands fold (the same IEEE operation, done once);
//   - the jets' own structural zeros (the Hessian of x, the y-derivatives of
//     a function of x) absorb products and vanish from sums;
//   - products and quotients by 1 are dropped (exact);
//   - equal instructions are recorded once;
//   - negations fold into a neighbouring multiply, divide, add or subtract
//     where that gives the same bits: (-a) * c == a * (-c) in IEEE
//     arithmetic.
// formula_tape.cpp then orders the instructions and allocates registers.
#include "problems/formula.hpp"

#include <algorithm>
#include <bit>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

namespace rb {
namespace {

class TapeBuilder;

// A scalar of the lowering: a constant, or the value of instruction `id`.
struct Sym {
  TapeBuilder* builder = nullptr;  // set for values
  int id = -1;                     // -1: a constant
  double c = 0.0;                  // the constant
  // A constant of the jet ops themselves (T(0.0), T(1.0), ...), as opposed
  // to one of the formula: only the jets' own zeros absorb products, so the
  // value part computes x * 0 for a formula's 0 just as value() does.
  bool structural = true;

  Sym() = default;
  explicit Sym(double v, bool is_structural = true) : c(v), structural(is_structural) {}

  bool is_const() const { return id < 0; }
  bool is_zero() const { return is_const() && structural && c == 0.0; }
  bool is_one() const { return is_const() && c == 1.0; }
};

// A formula's constant in an op with a jet (u + c, c * u, pow(u, c), ...).
Sym numeric(double c) { return Sym(c, false); }

class TapeBuilder {
 public:
  Sym input(int id) { return value(id); }

  // r op r, r op c, c op r: emitted once per distinct instruction.
  Sym emit(TapeCode code, const Sym& a, const Sym& b = Sym(), double c = 0.0) {
    const int ia = a.id, ib = b.is_const() ? -1 : b.id;
    // by the constant's bits: NaN orders nowhere, and 0 and -0 differ
    const auto key = std::make_tuple(code, ia, ib, std::bit_cast<std::uint64_t>(c));
    const auto found = memo_.find(key);
    if (found != memo_.end()) return value(found->second);
    nodes_.push_back({code, ia, ib, c});
    const int id = static_cast<int>(nodes_.size()) + 1;
    memo_.emplace(key, id);
    return value(id);
  }

  // The instruction defining value id, or nullptr for x and y.
  const TapeNode* node(int id) const { return id >= 2 ? &nodes_[static_cast<std::size_t>(id - 2)] : nullptr; }
  const std::vector<TapeNode>& nodes() const { return nodes_; }

 private:
  Sym value(int id) {
    Sym s;
    s.builder = this;
    s.id = id;
    return s;
  }

  std::vector<TapeNode> nodes_;
  std::map<std::tuple<TapeCode, int, int, std::uint64_t>, int> memo_;
};

// value id's instruction when it is a negation: its operand, else -1
int negated(const Sym& s) {
  const TapeNode* n = s.is_const() ? nullptr : s.builder->node(s.id);
  return n && n->code == TapeCode::neg ? n->a : -1;
}
Sym operand_of_neg(const Sym& s) {
  Sym r = s;
  r.id = negated(s);
  return r;
}

// -- arithmetic ----------------------------------------------------------------

Sym operator-(const Sym& u) {
  if (u.is_const()) return Sym(-u.c, u.structural);
  if (negated(u) >= 0) return operand_of_neg(u);
  // into the op that made u, where that gives the same bits, signed zeros
  // included: -(a c) == a (-c), -(a / c) == a / (-c), -(c / a) == (-c) / a
  if (const TapeNode* made = u.builder->node(u.id)) {
    const TapeNode n = *made;
    Sym a = u;
    a.id = n.a;
    if (n.code == TapeCode::mul_c || n.code == TapeCode::div_c || n.code == TapeCode::rdiv_c)
      return u.builder->emit(n.code, a, Sym(), -n.c);
  }
  return u.builder->emit(TapeCode::neg, u);
}

Sym fold(double v, const Sym& a, const Sym& b) { return Sym(v, a.structural && b.structural); }

Sym operator+(const Sym& a, const Sym& b) {
  if (a.is_zero()) return b;
  if (b.is_zero()) return a;
  if (a.is_const() && b.is_const()) return fold(a.c + b.c, a, b);
  if (a.is_const()) return b.builder->emit(TapeCode::add_c, b, Sym(), a.c);
  if (b.is_const()) return a.builder->emit(TapeCode::add_c, a, Sym(), b.c);
  // (-a) + b == b - a, a + (-b) == a - b
  if (negated(a) >= 0) return a.builder->emit(TapeCode::sub, b, operand_of_neg(a));
  if (negated(b) >= 0) return a.builder->emit(TapeCode::sub, a, operand_of_neg(b));
  return a.id <= b.id ? a.builder->emit(TapeCode::add, a, b) : a.builder->emit(TapeCode::add, b, a);
}

Sym operator-(const Sym& a, const Sym& b) {
  if (b.is_zero()) return a;
  if (a.is_zero()) return -b;
  if (a.is_const() && b.is_const()) return fold(a.c - b.c, a, b);
  if (a.is_const()) return b.builder->emit(TapeCode::rsub_c, b, Sym(), a.c);
  // a - c == a + (-c) exactly
  if (b.is_const()) return a.builder->emit(TapeCode::add_c, a, Sym(), -b.c);
  if (negated(b) >= 0) return a + operand_of_neg(b);
  return a.builder->emit(TapeCode::sub, a, b);
}

Sym operator*(const Sym& a, const Sym& b) {
  if (a.is_zero() || b.is_zero()) return Sym(0.0);
  if (a.is_one()) return b;
  if (b.is_one()) return a;
  if (a.is_const() && b.is_const()) return fold(a.c * b.c, a, b);
  if (a.is_const() || b.is_const()) {
    const Sym& u = a.is_const() ? b : a;
    const double c = a.is_const() ? a.c : b.c;
    if (negated(u) >= 0) return u.builder->emit(TapeCode::mul_c, operand_of_neg(u), Sym(), -c);
    return u.builder->emit(TapeCode::mul_c, u, Sym(), c);
  }
  return a.id <= b.id ? a.builder->emit(TapeCode::mul, a, b) : a.builder->emit(TapeCode::mul, b, a);
}

Sym operator/(const Sym& a, const Sym& b) {
  if (a.is_zero()) return Sym(0.0);
  if (b.is_one()) return a;
  if (a.is_const() && b.is_const()) return fold(a.c / b.c, a, b);
  if (a.is_const()) return b.builder->emit(TapeCode::rdiv_c, b, Sym(), a.c);
  if (b.is_const()) {
    if (negated(a) >= 0) return a.builder->emit(TapeCode::div_c, operand_of_neg(a), Sym(), -b.c);
    return a.builder->emit(TapeCode::div_c, a, Sym(), b.c);
  }
  return a.builder->emit(TapeCode::div, a, b);
}

// with a formula's constant (the forms the jet ops use)
Sym operator+(const Sym& a, double c) { return a + numeric(c); }
Sym operator-(double c, const Sym& a) { return numeric(c) - a; }
Sym operator*(const Sym& a, double c) { return a * numeric(c); }
Sym operator*(double c, const Sym& a) { return numeric(c) * a; }
Sym operator/(const Sym& a, double c) { return a / numeric(c); }
Sym operator/(double c, const Sym& a) { return numeric(c) / a; }

// -- functions -----------------------------------------------------------------

// g(u): folded for a constant u, else one instruction
template <double (*G)(double)>
Sym apply(TapeCode code, const Sym& u) {
  if (u.is_const()) return numeric(G(u.c));
  return u.builder->emit(code, u);
}

// g(a, b) for two-argument functions, with the c-op-r and r-op-c forms
template <double (*G)(double, double)>
Sym apply2(TapeCode rr, TapeCode rc, TapeCode cr, const Sym& a, const Sym& b) {
  if (a.is_const() && b.is_const()) return numeric(G(a.c, b.c));
  if (a.is_const()) return b.builder->emit(cr, b, Sym(), a.c);
  if (b.is_const()) return a.builder->emit(rc, a, Sym(), b.c);
  return a.builder->emit(rr, a, b);
}

double sin_d(double u) { return std::sin(u); }
double cos_d(double u) { return std::cos(u); }
double tan_d(double u) { return std::tan(u); }
double asin_d(double u) { return std::asin(u); }
double acos_d(double u) { return std::acos(u); }
double atan_d(double u) { return std::atan(u); }
double sinh_d(double u) { return std::sinh(u); }
double cosh_d(double u) { return std::cosh(u); }
double tanh_d(double u) { return std::tanh(u); }
double exp_d(double u) { return std::exp(u); }
double log_d(double u) { return std::log(u); }
double sqrt_d(double u) { return std::sqrt(u); }
double pow_d(double a, double b) { return std::pow(a, b); }
double atan2_d(double a, double b) { return std::atan2(a, b); }
double hypot_d(double a, double b) { return std::hypot(a, b); }

Sym sin(const Sym& u) { return apply<sin_d>(TapeCode::sin, u); }
Sym cos(const Sym& u) { return apply<cos_d>(TapeCode::cos, u); }
Sym tan(const Sym& u) { return apply<tan_d>(TapeCode::tan, u); }
Sym asin(const Sym& u) { return apply<asin_d>(TapeCode::asin, u); }
Sym acos(const Sym& u) { return apply<acos_d>(TapeCode::acos, u); }
Sym atan(const Sym& u) { return apply<atan_d>(TapeCode::atan, u); }
Sym sinh(const Sym& u) { return apply<sinh_d>(TapeCode::sinh, u); }
Sym cosh(const Sym& u) { return apply<cosh_d>(TapeCode::cosh, u); }
Sym tanh(const Sym& u) { return apply<tanh_d>(TapeCode::tanh, u); }
Sym exp(const Sym& u) { return apply<exp_d>(TapeCode::exp, u); }
Sym log(const Sym& u) { return apply<log_d>(TapeCode::log, u); }
Sym sqrt(const Sym& u) { return apply<sqrt_d>(TapeCode::sqrt, u); }
Sym pow(const Sym& a, const Sym& b) { return apply2<pow_d>(TapeCode::pow, TapeCode::pow_c, TapeCode::rpow_c, a, b); }
Sym pow(const Sym& a, double c) { return pow(a, numeric(c)); }
Sym pow(double c, const Sym& b) { return pow(numeric(c), b); }
Sym atan2(const Sym& a, const Sym& b) {
  return apply2<atan2_d>(TapeCode::atan2, TapeCode::atan2_c, TapeCode::ratan2_c, a, b);
}
Sym hypot(const Sym& a, const Sym& b) {
  return apply2<hypot_d>(TapeCode::hypot, TapeCode::hypot_c, TapeCode::rhypot_c, a, b);
}

}  // namespace

// the lowering's scalar calls its own functions directly (jet.hpp)
template <>
inline constexpr bool jet_detail::is_direct_v<Sym> = true;

// a jet's value part is never a structural constant: x^0 - y^0 is a
// formula's 0, and x^a * (x^0 - y^0) is NaN where x^a is, as in value()
template <>
inline Sym jet_detail::value_constant<Sym>(double c) {
  return numeric(c);
}

void Formula::lower_to_tape() {
  tape_ = FormulaTape();
  // deep or long formulas keep the stack machine: their tape would not fit
  // the register file, and lowering them would cost more than it saves
  constexpr std::size_t kMaxProgram = 4096;
  if (max_stack_ > kSmallStack || program_.size() > kMaxProgram) return;

  TapeBuilder b;
  const Jet2<Sym> jet = run<Sym, kSmallStack>(b.input(0), b.input(1));
  const std::array<int, 6> outputs = {jet.f.id, jet.fx.id, jet.fy.id, jet.fxx.id, jet.fxy.id, jet.fyy.id};
  const Jet2<double> constants = {jet.f.c, jet.fx.c, jet.fy.c, jet.fxx.c, jet.fxy.c, jet.fyy.c};
  std::optional<TapeProgram> full = build_tape(b.nodes(), outputs, constants);
  std::array<int, 6> slope_outputs = outputs;
  slope_outputs[0] = -1;
  Jet2<double> slope_constants = constants;
  slope_constants.f = std::nan("");
  std::optional<TapeProgram> slopes = build_tape(b.nodes(), slope_outputs, slope_constants);
  if (!full || !slopes) return;
  tape_.full = std::move(*full);
  tape_.slopes = std::move(*slopes);
  tape_.usable_ = true;
}

}  // namespace rb

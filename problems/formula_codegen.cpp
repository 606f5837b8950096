// The tape as C (formula_codegen.hpp): one statement per TapeOp, mirroring
// TapeProgram::run case by case. GCC's and clang's builtins stand in for
// <math.h>, so the generated file needs no headers.
#include "problems/formula_codegen.hpp"

#include <bit>
#include <cstdio>
#include <set>

namespace rb {
namespace {

std::string reg(int i) {
  std::string s = std::to_string(i);
  return s.insert(0, 1, 'r');  // not "r" + ...: GCC 12 warns falsely (-Wrestrict) on that
}

// A constant by its bits: exact for every double, NaN payloads and -0 included.
std::string constant(double c) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "rb_c(0x%016llxULL)",
                static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(c)));
  return buf;
}

// The right-hand side of `d = ...` for one op (all but sincos/cossin).
std::string expression(const TapeOp& op, const std::string& a) {
  const std::string b = reg(op.b), c = constant(op.c);
  const auto call = [](const char* f, const std::string& u, const std::string& v = {}) {
    return std::string("__builtin_") + f + "(" + u + (v.empty() ? "" : ", " + v) + ")";
  };
  switch (op.code) {
    case TapeCode::add: return a + " + " + b;
    case TapeCode::sub: return a + " - " + b;
    case TapeCode::mul: return a + " * " + b;
    case TapeCode::div: return a + " / " + b;
    case TapeCode::pow: return call("pow", a, b);
    case TapeCode::atan2: return call("atan2", a, b);
    case TapeCode::hypot: return call("hypot", a, b);
    case TapeCode::add_c: return a + " + " + c;
    case TapeCode::mul_c: return a + " * " + c;
    case TapeCode::div_c: return a + " / " + c;
    case TapeCode::pow_c: return call("pow", a, c);
    case TapeCode::atan2_c: return call("atan2", a, c);
    case TapeCode::hypot_c: return call("hypot", a, c);
    case TapeCode::rsub_c: return c + " - " + a;
    case TapeCode::rdiv_c: return c + " / " + a;
    case TapeCode::rpow_c: return call("pow", c, a);
    case TapeCode::ratan2_c: return call("atan2", c, a);
    case TapeCode::rhypot_c: return call("hypot", c, a);
    case TapeCode::neg: return "-" + a;
    case TapeCode::sin: return call("sin", a);
    case TapeCode::cos: return call("cos", a);
    case TapeCode::tan: return call("tan", a);
    case TapeCode::asin: return call("asin", a);
    case TapeCode::acos: return call("acos", a);
    case TapeCode::atan: return call("atan", a);
    case TapeCode::sinh: return call("sinh", a);
    case TapeCode::cosh: return call("cosh", a);
    case TapeCode::tanh: return call("tanh", a);
    case TapeCode::exp: return call("exp", a);
    case TapeCode::log: return call("log", a);
    case TapeCode::sqrt: return call("sqrt", a);
    case TapeCode::sincos:
    case TapeCode::cossin: break;
  }
  return "0.0 / 0.0";  // not reached: sincos is written by function_source
}

std::string function_source(const TapeProgram& p, const char* name) {
  std::set<int> used = {0, 1};
  for (const TapeOp& op : p.ops()) {
    used.insert(op.dst);
    used.insert(op.a);
    used.insert(op.b);
  }
  std::string s = "void " + std::string(name) + "(double x, double y, double* out) {\n  double";
  for (const int r : used) s += (r == 0 ? " " : ", ") + reg(r) + (r == 0 ? " = x" : r == 1 ? " = y" : " = 0.0");
  s += ";\n  double last = " + std::string(p.first_input() == 0 ? "x" : "y") + ", d;\n";
  for (const TapeOp& op : p.ops()) {
    const std::string a = op.chained ? "last" : reg(op.a);
    if (op.code == TapeCode::sincos || op.code == TapeCode::cossin) {
      const bool cos_first = op.code == TapeCode::cossin;
      s += "  { double s, c; __builtin_sincos(" + a + ", &s, &c); d = " + (cos_first ? "c" : "s") + "; " + reg(op.b) +
           " = " + (cos_first ? "s" : "c") + "; }\n";
    } else {
      s += "  d = " + expression(op, a) + ";\n";
    }
    s += "  " + reg(op.dst) + " = d; last = d;\n";
  }
  const Jet2<double>& c = p.constant_parts();
  const double constants[6] = {c.f, c.fx, c.fy, c.fxx, c.fxy, c.fyy};
  for (std::size_t i = 0; i < 6; ++i) {
    const int src = p.output(i);
    const std::string value = src >= 0 ? reg(src) : src == TapeProgram::kLast ? "last" : constant(constants[i]);
    s += "  out[" + std::to_string(i) + "] = " + value + ";\n";
  }
  return s + "}\n";
}

}  // namespace

std::string formula_c_source(const FormulaTape& tape) {
  std::string s =
      "/* rollbench native landscape, generated from a formula's tape */\n"
      "static inline double rb_c(unsigned long long bits) {\n"
      "  double d; __builtin_memcpy(&d, &bits, sizeof d); return d;\n"
      "}\n";
  s += function_source(tape.full, "rb_formula_full");
  s += function_source(tape.slopes, "rb_formula_slopes");
  return s;
}

}  // namespace rb

// Formula text to the stack program of formula.hpp: the recursive-descent
// compiler with constant folding, and Formula::parse. The tokens come from
// formula_lexer.hpp.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "problems/formula.hpp"
#include "problems/formula_lexer.hpp"

namespace rb {
namespace {

using formula_detail::Lexer;
using formula_detail::quoted;
using formula_detail::Tok;
using formula_detail::Token;

struct FunctionInfo {
  std::string_view name;
  OpCode code;
  int arity;
};

constexpr std::array<FunctionInfo, 14> kFunctions = {{
    {"sin", OpCode::sin, 1},
    {"cos", OpCode::cos, 1},
    {"tan", OpCode::tan, 1},
    {"asin", OpCode::asin, 1},
    {"acos", OpCode::acos, 1},
    {"atan", OpCode::atan, 1},
    {"sinh", OpCode::sinh, 1},
    {"cosh", OpCode::cosh, 1},
    {"tanh", OpCode::tanh, 1},
    {"exp", OpCode::exp, 1},
    {"log", OpCode::log, 1},
    {"sqrt", OpCode::sqrt, 1},
    {"atan2", OpCode::atan2, 2},
    {"hypot", OpCode::hypot, 2},
}};

// Rejected because the equations of motion need f in C^2; each with a
// smooth stand-in the user can write instead.
struct NonSmoothInfo {
  std::string_view name;
  std::string_view hint;
};

constexpr std::string_view kStaircase = "use x - sin(2*pi*x)/(2*pi) for a smooth staircase";
constexpr std::array<NonSmoothInfo, 7> kNonSmooth = {{
    {"abs", "use sqrt(x^2 + eps) for a smooth stand-in"},
    {"min", "use (a + b - sqrt((a - b)^2 + eps))/2 for a smooth stand-in"},
    {"max", "use (a + b + sqrt((a - b)^2 + eps))/2 for a smooth stand-in"},
    {"sign", "use tanh(x/eps) for a smooth stand-in"},
    {"floor", kStaircase},
    {"ceil", kStaircase},
    {"round", kStaircase},
}};

template <class Table>
const typename Table::value_type* find_in(const Table& table, std::string_view name) {
  for (const auto& entry : table)
    if (entry.name == name) return &entry;
  return nullptr;
}
const FunctionInfo* find_function(std::string_view name) { return find_in(kFunctions, name); }
const NonSmoothInfo* find_non_smooth(std::string_view name) { return find_in(kNonSmooth, name); }

// The variables and constants a formula knows without params.
struct NamedValue {
  std::string_view name;
  OpCode variable;  // push_x or push_y; push_const for a constant
  double value = 0.0;
};
constexpr std::array<NamedValue, 4> kNamedValues = {{
    {"x", OpCode::push_x},
    {"y", OpCode::push_y},
    {"pi", OpCode::push_const, std::numbers::pi},
    {"e", OpCode::push_const, std::numbers::e},
}};
const NamedValue* find_named_value(std::string_view name) { return find_in(kNamedValues, name); }

template <class Table>
std::string names_of(const Table& table, std::string_view separator) {
  std::string out;
  for (const auto& entry : table) out.append(out.empty() ? "" : separator).append(entry.name);
  return out;
}

std::string lowercase(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](char c) { return c >= 'A' && c <= 'Z' ? char(c + 32) : c; });
  return out;
}

bool is_binary(OpCode c) { return c >= OpCode::add && c <= OpCode::hypot; }
bool is_push(OpCode c) { return c <= OpCode::push_y; }

// Exponents that are integers this small use repeated multiplication: exact
// at u = 0 and for negative u.
constexpr double kMaxIntExponent = 1 << 20;

// Recursive descent straight to stack code. A constant operand is kept
// aside (not emitted) until an op with a variable operand needs it, so
// constant sub-expressions fold and constants become immediates.
class Compiler {
 public:
  Compiler(std::string_view text, const std::map<std::string, double>& params) : lex_(text), params_(params) {}

  std::vector<Op> compile() {
    advance();
    Operand result = parse_sum();
    if (tok().kind == Tok::rparen) fail("')' has no matching '('", tok());
    if (tok().kind == Tok::comma) fail("',' outside a function's argument list", tok());
    if (tok().kind != Tok::end) fail("expected an operator before " + describe(tok()), tok());
    if (result.is_const) emit({OpCode::push_const, 0, result.value});
    return std::move(code_);
  }

 private:
  struct Operand {
    bool is_const = false;
    double value = 0.0;     // when is_const
    std::size_t start = 0;  // otherwise: where its code begins in code_
  };

  // One more level of nesting for as long as it lives.
  class Nest {
   public:
    Nest(Compiler& c, const Token& at) : c_(c) {
      if (++c_.depth_ > Formula::kMaxDepth)
        c_.fail("formula nests deeper than " + std::to_string(Formula::kMaxDepth) + " levels", at);
    }
    ~Nest() { --c_.depth_; }
    Nest(const Nest&) = delete;
    Nest& operator=(const Nest&) = delete;

   private:
    Compiler& c_;
  };

  [[noreturn]] void fail(const std::string& message, const Token& at) const { Lexer::fail(message, at.pos); }

  const Token& tok() const { return lex_.token(); }
  void advance() { lex_.advance(); }
  std::string_view spelling(const Token& t) const { return lex_.spelling(t); }
  std::string describe(const Token& t) const { return lex_.describe(t); }

  // -- grammar -------------------------------------------------------------

  // sum := product (('+' | '-') product)*
  Operand parse_sum() {
    Operand left = parse_product();
    while (tok().kind == Tok::plus || tok().kind == Tok::minus) {
      const OpCode code = tok().kind == Tok::plus ? OpCode::add : OpCode::sub;
      advance();
      left = binary(code, left, parse_product());
    }
    return left;
  }

  // product := unary (('*' | '/') unary)*
  Operand parse_product() {
    Operand left = parse_unary();
    while (tok().kind == Tok::star || tok().kind == Tok::slash) {
      const OpCode code = tok().kind == Tok::star ? OpCode::mul : OpCode::div;
      advance();
      left = binary(code, left, parse_unary());
    }
    return left;
  }

  // unary := ('-' | '+') unary | power; so -x^2 = -(x^2)
  Operand parse_unary() {
    if (tok().kind != Tok::plus && tok().kind != Tok::minus) return parse_power();
    const bool minus = tok().kind == Tok::minus;
    Nest nest(*this, tok());
    advance();
    const Operand u = parse_unary();
    return minus ? unary(OpCode::neg, u) : u;
  }

  // power := primary (('^' | '**') unary)?: right-associative, 2^-x allowed
  Operand parse_power() {
    const Operand base = parse_primary();
    if (tok().kind != Tok::power) return base;
    Nest nest(*this, tok());
    advance();
    return binary(OpCode::pow, base, parse_unary());
  }

  Operand parse_primary() {
    switch (tok().kind) {
      case Tok::number: {
        const double v = tok().number;
        advance();
        return {true, v, 0};
      }
      case Tok::lparen: {
        const Token open = tok();
        Nest nest(*this, open);
        advance();
        const Operand inner = parse_sum();
        if (tok().kind == Tok::rparen) {
          advance();
          return inner;
        }
        if (tok().kind == Tok::end) fail("missing ')' to close this '('", open);
        if (tok().kind == Tok::comma) fail("',' outside a function's argument list", tok());
        fail("expected an operator or ')' before " + describe(tok()), tok());
      }
      case Tok::name: return parse_name();
      default:
        if (lex_.previous().len == 0) fail("expected an operand, found " + describe(tok()), tok());
        fail("expected an operand after " + describe(lex_.previous()), tok());
    }
  }

  Operand parse_name() {
    const Token name_tok = tok();
    const std::string_view name = spelling(name_tok);
    advance();
    const bool call = tok().kind == Tok::lparen;
    if (const NonSmoothInfo* ns = find_non_smooth(name))
      fail(std::string(name) + " is not smooth: the landscape needs continuous second derivatives (docs/model.md); " +
               std::string(ns->hint),
           name_tok);
    if (const FunctionInfo* fn = find_function(name)) {
      if (!call) fail(std::string(name) + " is a function: write " + std::string(name) + "(...)", name_tok);
      return parse_call(*fn, name_tok);
    }
    const auto param = params_.find(std::string(name));
    const NamedValue* named = find_named_value(name);
    const bool known = named || param != params_.end();
    if (call && known)
      fail(quoted(name) + " is not a function; write " + std::string(name) + "*(...) for a product", name_tok);
    if (named && named->variable != OpCode::push_const) return emit_variable(named->variable);
    if (named) return {true, named->value, 0};
    if (param != params_.end()) return {true, param->second, 0};
    std::string message = (call ? "unknown function " : "unknown name ") + quoted(name);
    const std::string lower = lowercase(name);
    if (lower != name && (find_function(lower) || find_named_value(lower)))
      message += "; names are case-sensitive: did you mean '" + lower + "'?";
    else if (call) message += "; the functions are " + names_of(kFunctions, " ");
    else message += "; a formula knows " + names_of(kNamedValues, ", ") + known_params();
    fail(message, name_tok);
  }

  std::string known_params() const {
    if (params_.empty()) return " and no params";
    constexpr std::size_t kListed = 8;
    std::string list = " and the params";
    std::size_t i = 0;
    for (const auto& entry : params_) {
      if (i++ == kListed) return list + ", ...";
      list += (i == 1 ? " " : ", ") + entry.first;
    }
    return list;
  }

  // name '(' [sum (',' sum)*] ')'
  Operand parse_call(const FunctionInfo& fn, const Token& name_tok) {
    const Token open = tok();
    Nest nest(*this, open);
    advance();
    std::array<Operand, 2> args;
    int count = 0;
    if (tok().kind != Tok::rparen) {
      for (;; advance()) {  // past each ','
        const Operand a = parse_sum();
        if (count < 2) args[count] = a;
        ++count;
        if (tok().kind != Tok::comma) break;
      }
      if (tok().kind == Tok::end) fail("missing ')' to close this '('", open);
      if (tok().kind != Tok::rparen) fail("expected an operator, ',' or ')' before " + describe(tok()), tok());
    }
    advance();
    if (count != fn.arity)
      fail(std::string(fn.name) + " takes " + std::to_string(fn.arity) + (fn.arity == 1 ? " argument" : " arguments") +
               ", got " + std::to_string(count),
           name_tok);
    return fn.arity == 1 ? unary(fn.code, args[0]) : binary(fn.code, args[0], args[1]);
  }

  // -- code ----------------------------------------------------------------

  void emit(const Op& op) { code_.push_back(op); }

  Operand emit_variable(OpCode code) {
    const Operand v{false, 0.0, code_.size()};
    emit({code});
    return v;
  }

  Operand unary(OpCode code, const Operand& u) {
    if (u.is_const) return {true, formula_detail::value_op({code}, u.value, 0.0), 0};
    emit({code});
    return u;
  }

  Operand binary(OpCode code, const Operand& a, const Operand& b) {
    if (a.is_const && b.is_const) return {true, formula_detail::value_op({code}, a.value, b.value), 0};
    if (b.is_const) {
      const double c = b.value;
      switch (code) {
        // u - c is u + (-c) exactly in IEEE arithmetic
        case OpCode::add: emit({OpCode::add_const, 0, c}); break;
        case OpCode::sub: emit({OpCode::add_const, 0, -c}); break;
        case OpCode::mul: emit({OpCode::mul_const, 0, c}); break;
        case OpCode::div: emit({OpCode::div_const, 0, c}); break;
        case OpCode::pow:
          if (c == std::trunc(c) && std::abs(c) <= kMaxIntExponent) emit({OpCode::pow_int, static_cast<int>(c), c});
          else emit({OpCode::pow_const, 0, c});
          break;
        default: emit({OpCode::push_const, 0, c}); emit({code});
      }
      return a;
    }
    if (a.is_const) {
      const double c = a.value;
      switch (code) {
        // c + u and c * u are commutative in IEEE arithmetic
        case OpCode::add: emit({OpCode::add_const, 0, c}); break;
        case OpCode::sub: emit({OpCode::rsub_const, 0, c}); break;
        case OpCode::mul: emit({OpCode::mul_const, 0, c}); break;
        case OpCode::div: emit({OpCode::rdiv_const, 0, c}); break;
        case OpCode::pow: emit({OpCode::rpow_const, 0, c}); break;
        default:
          // atan2(c, u), hypot(c, u): c goes below u's code
          code_.insert(code_.begin() + static_cast<std::ptrdiff_t>(b.start), Op{OpCode::push_const, 0, c});
          emit({code});
      }
      return b;
    }
    emit({code});
    return a;
  }

  Lexer lex_;
  const std::map<std::string, double>& params_;
  int depth_ = 0;
  std::vector<Op> code_;
};

void check_params(const std::map<std::string, double>& params) {
  for (const auto& [name, value] : params) {
    check_formula_param_name(name);
    if (!std::isfinite(value)) throw InputError("param " + quoted(name) + " is not finite");
  }
}

}  // namespace

std::vector<std::string_view> formula_reserved_names() {
  std::vector<std::string_view> names;
  for (const auto& v : kNamedValues) names.push_back(v.name);
  for (const auto& f : kFunctions) names.push_back(f.name);
  for (const auto& n : kNonSmooth) names.push_back(n.name);
  return names;
}

void check_formula_param_name(std::string_view name) {
  if (!formula_detail::is_name(name))
    throw InputError("param name " + quoted(name) +
                     " is not a name: use letters, digits and '_', starting with a letter or '_'");
  if (find_named_value(name) || find_function(name) || find_non_smooth(name))
    throw InputError("param " + quoted(name) + " shadows a name of the formula language (" +
                     names_of(kNamedValues, " ") + " " + names_of(kFunctions, " ") + " " + names_of(kNonSmooth, " ") +
                     "); rename it");
}

Formula::Formula() : text_("0"), program_{Op{OpCode::push_const, 0, 0.0}}, max_stack_(1) { lower_to_tape(); }

Formula Formula::parse(std::string_view text, const std::map<std::string, double>& params) {
  if (text.size() > kMaxLength)
    throw InputError(
        "formula is " + std::to_string(text.size()) + " characters long; the limit is " + std::to_string(kMaxLength),
        "", static_cast<int>(kMaxLength + 1));
  if (text.find_first_not_of(formula_detail::kSpace) == std::string_view::npos)
    throw InputError("empty formula", "", 1);
  check_params(params);

  Formula f;
  f.text_ = std::string(text);
  f.program_ = Compiler(text, params).compile();
  // the stack depth the program reaches, checked against the fixed stack
  std::size_t depth = 0;
  f.max_stack_ = 0;
  for (const Op& op : f.program_) {
    if (is_push(op.code)) ++depth;
    if (is_binary(op.code)) --depth;
    f.max_stack_ = std::max(f.max_stack_, depth);
  }
  if (f.max_stack_ > kMaxStack)
    throw InputError("formula needs a stack deeper than " + std::to_string(kMaxStack) + " entries", "", 1);
  f.lower_to_tape();
  return f;
}

}  // namespace rb

#include "problems/formula.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace rb {
namespace {

struct FunctionInfo {
  std::string_view name;
  OpCode code;
  int arity;
};

constexpr std::array<FunctionInfo, 14> kFunctions = {{
    {"sin", OpCode::sin, 1},   {"cos", OpCode::cos, 1},     {"tan", OpCode::tan, 1},
    {"asin", OpCode::asin, 1}, {"acos", OpCode::acos, 1},   {"atan", OpCode::atan, 1},
    {"sinh", OpCode::sinh, 1}, {"cosh", OpCode::cosh, 1},   {"tanh", OpCode::tanh, 1},
    {"exp", OpCode::exp, 1},   {"log", OpCode::log, 1},     {"sqrt", OpCode::sqrt, 1},
    {"atan2", OpCode::atan2, 2}, {"hypot", OpCode::hypot, 2},
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

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }

bool is_name(std::string_view s) {
  return !s.empty() && is_name_start(s[0]) && std::all_of(s.begin(), s.end(), is_name_char);
}

// A name or number quoted for a message, cut short so that a hostile
// formula cannot make a huge message.
std::string quoted(std::string_view s) {
  constexpr std::size_t kShown = 32;
  if (s.size() <= kShown) return "'" + std::string(s) + "'";
  return "'" + std::string(s.substr(0, kShown)) + "...'";
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

enum class Tok { number, name, plus, minus, star, slash, power, lparen, rparen, comma, end };

constexpr std::string_view kSpace = " \t\r\n";
constexpr std::string_view kPunctuation = "+-*/^(),";
constexpr std::array<Tok, 8> kPunctuationTok = {Tok::plus,  Tok::minus,  Tok::star,   Tok::slash,
                                                Tok::power, Tok::lparen, Tok::rparen, Tok::comma};

struct Token {
  Tok kind = Tok::end;
  std::size_t pos = 0, len = 0;  // where in the text
  double number = 0.0;           // the value of a number
};

// Recursive descent straight to stack code. A constant operand is kept
// aside (not emitted) until an op with a variable operand needs it, so
// constant sub-expressions fold and constants become immediates.
class Compiler {
 public:
  Compiler(std::string_view text, const std::map<std::string, double>& params)
      : text_(text), params_(params) {}

  std::vector<Op> compile() {
    advance();
    Operand result = parse_sum();
    if (tok_.kind == Tok::rparen) fail("')' has no matching '('", tok_);
    if (tok_.kind == Tok::comma) fail("',' outside a function's argument list", tok_);
    if (tok_.kind != Tok::end) fail("expected an operator before " + describe(tok_), tok_);
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

  [[noreturn]] void fail(const std::string& message, std::size_t pos) const {
    throw InputError(message, "", static_cast<int>(pos + 1));
  }
  [[noreturn]] void fail(const std::string& message, const Token& at) const { fail(message, at.pos); }

  std::string_view spelling(const Token& t) const { return text_.substr(t.pos, t.len); }
  std::string describe(const Token& t) const {
    return t.kind == Tok::end ? "the end of the formula" : quoted(spelling(t));
  }

  // -- lexer ---------------------------------------------------------------

  void advance() {
    prev_ = tok_;
    tok_ = lex();
  }

  Token lex() {
    pos_ = std::min(text_.find_first_not_of(kSpace, pos_), text_.size());
    const std::size_t start = pos_;
    if (pos_ == text_.size()) return {Tok::end, start, 0};
    const char c = text_[pos_];
    if (is_digit(c) || (c == '.' && at_digit(pos_ + 1))) return lex_number();
    if (is_name_start(c)) {
      while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
      return {Tok::name, start, pos_ - start};
    }
    if (text_.substr(pos_, 2) == "**") {
      pos_ += 2;
      return {Tok::power, start, 2};
    }
    const std::size_t k = kPunctuation.find(c);
    if (k == std::string_view::npos) unexpected_character(start);
    ++pos_;
    return {kPunctuationTok[k], start, 1};
  }

  bool at_digit(std::size_t i) const { return i < text_.size() && is_digit(text_[i]); }

  [[noreturn]] void unexpected_character(std::size_t at) const {
    const auto byte = static_cast<unsigned char>(text_[at]);
    if (byte >= 0x20 && byte < 0x7f) fail("unexpected character '" + std::string(1, text_[at]) + "'", at);
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", byte);
    if (byte >= 0x80)
      fail(std::string("unexpected non-ASCII character (byte ") + hex + "); formulas are plain ASCII", at);
    fail(std::string("unexpected control character (byte ") + hex + ")", at);
  }

  // digits [. digits] [(e|E) [+|-] digits], or . digits
  Token lex_number() {
    const std::size_t start = pos_;
    std::size_t i = pos_;
    while (at_digit(i)) ++i;
    if (i < text_.size() && text_[i] == '.') {
      ++i;
      while (at_digit(i)) ++i;
    }
    bool bad = false;
    if (i < text_.size() && (text_[i] == 'e' || text_[i] == 'E')) {
      std::size_t j = i + 1;
      if (j < text_.size() && (text_[j] == '+' || text_[j] == '-')) ++j;
      if (at_digit(j)) {
        i = j;
        while (at_digit(i)) ++i;
      } else {
        bad = true;
      }
    }
    if (bad || (i < text_.size() && (is_name_char(text_[i]) || text_[i] == '.'))) {
      // the malformed run: name characters, dots, and signs after an exponent mark
      i = start;
      const auto exponent_sign = [&](std::size_t k) {
        return (text_[k] == '+' || text_[k] == '-') && (text_[k - 1] == 'e' || text_[k - 1] == 'E');
      };
      while (i < text_.size() && (is_name_char(text_[i]) || text_[i] == '.' || exponent_sign(i))) ++i;
      fail("malformed number " + quoted(text_.substr(start, i - start)), start);
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text_.data() + start, text_.data() + i, value);
    if (ec != std::errc() || end != text_.data() + i)
      fail("number " + quoted(text_.substr(start, i - start)) + " is out of range for a double", start);
    pos_ = i;
    return {Tok::number, start, i - start, value};
  }

  // -- grammar -------------------------------------------------------------

  // sum := product (('+' | '-') product)*
  Operand parse_sum() {
    Operand left = parse_product();
    while (tok_.kind == Tok::plus || tok_.kind == Tok::minus) {
      const OpCode code = tok_.kind == Tok::plus ? OpCode::add : OpCode::sub;
      advance();
      left = binary(code, left, parse_product());
    }
    return left;
  }

  // product := unary (('*' | '/') unary)*
  Operand parse_product() {
    Operand left = parse_unary();
    while (tok_.kind == Tok::star || tok_.kind == Tok::slash) {
      const OpCode code = tok_.kind == Tok::star ? OpCode::mul : OpCode::div;
      advance();
      left = binary(code, left, parse_unary());
    }
    return left;
  }

  // unary := ('-' | '+') unary | power; so -x^2 = -(x^2)
  Operand parse_unary() {
    if (tok_.kind != Tok::plus && tok_.kind != Tok::minus) return parse_power();
    const bool minus = tok_.kind == Tok::minus;
    Nest nest(*this, tok_);
    advance();
    const Operand u = parse_unary();
    return minus ? unary(OpCode::neg, u) : u;
  }

  // power := primary (('^' | '**') unary)?: right-associative, 2^-x allowed
  Operand parse_power() {
    const Operand base = parse_primary();
    if (tok_.kind != Tok::power) return base;
    Nest nest(*this, tok_);
    advance();
    return binary(OpCode::pow, base, parse_unary());
  }

  Operand parse_primary() {
    switch (tok_.kind) {
      case Tok::number: {
        const double v = tok_.number;
        advance();
        return {true, v, 0};
      }
      case Tok::lparen: {
        const Token open = tok_;
        Nest nest(*this, open);
        advance();
        const Operand inner = parse_sum();
        if (tok_.kind == Tok::rparen) {
          advance();
          return inner;
        }
        if (tok_.kind == Tok::end) fail("missing ')' to close this '('", open);
        if (tok_.kind == Tok::comma) fail("',' outside a function's argument list", tok_);
        fail("expected an operator or ')' before " + describe(tok_), tok_);
      }
      case Tok::name: return parse_name();
      default:
        if (prev_.len == 0) fail("expected an operand, found " + describe(tok_), tok_);
        fail("expected an operand after " + describe(prev_), tok_);
    }
  }

  Operand parse_name() {
    const Token name_tok = tok_;
    const std::string_view name = spelling(name_tok);
    advance();
    const bool call = tok_.kind == Tok::lparen;
    if (const NonSmoothInfo* ns = find_non_smooth(name))
      fail(std::string(name) + " is not smooth: the landscape needs continuous second derivatives (MODEL.md); " +
               std::string(ns->hint),
           name_tok);
    if (const FunctionInfo* fn = find_function(name)) {
      if (!call) fail(std::string(name) + " is a function: write " + std::string(name) + "(...)", name_tok);
      return parse_call(*fn, name_tok);
    }
    const auto param = params_.find(std::string(name));
    const bool known = name == "x" || name == "y" || name == "pi" || name == "e" || param != params_.end();
    if (call && known)
      fail(quoted(name) + " is not a function; write " + std::string(name) + "*(...) for a product", name_tok);
    if (name == "x") return emit_variable(OpCode::push_x);
    if (name == "y") return emit_variable(OpCode::push_y);
    if (name == "pi") return {true, std::numbers::pi, 0};
    if (name == "e") return {true, std::numbers::e, 0};
    if (param != params_.end()) return {true, param->second, 0};
    std::string message = (call ? "unknown function " : "unknown name ") + quoted(name);
    const std::string lower = lowercase(name);
    if (lower != name && (find_function(lower) || lower == "x" || lower == "y" || lower == "pi" || lower == "e"))
      message += "; names are case-sensitive: did you mean '" + lower + "'?";
    else if (call)
      message += "; the functions are sin cos tan asin acos atan sinh cosh tanh exp log sqrt atan2 hypot";
    else
      message += "; a formula knows x, y, pi, e" + known_params();
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
    const Token open = tok_;
    Nest nest(*this, open);
    advance();
    std::array<Operand, 2> args;
    int count = 0;
    if (tok_.kind != Tok::rparen) {
      for (;; advance()) {  // past each ','
        const Operand a = parse_sum();
        if (count < 2) args[count] = a;
        ++count;
        if (tok_.kind != Tok::comma) break;
      }
      if (tok_.kind == Tok::end) fail("missing ')' to close this '('", open);
      if (tok_.kind != Tok::rparen) fail("expected an operator, ',' or ')' before " + describe(tok_), tok_);
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
          if (c == std::trunc(c) && std::abs(c) <= kMaxIntExponent)
            emit({OpCode::pow_int, static_cast<int>(c), c});
          else
            emit({OpCode::pow_const, 0, c});
          break;
        default:
          emit({OpCode::push_const, 0, c});
          emit({code});
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

  std::string_view text_;
  const std::map<std::string, double>& params_;
  std::size_t pos_ = 0;
  Token tok_, prev_;
  int depth_ = 0;
  std::vector<Op> code_;
};

void check_params(const std::map<std::string, double>& params) {
  for (const auto& [name, value] : params) {
    if (!is_name(name))
      throw InputError("param name " + quoted(name) +
                       " is not a name: use letters, digits and '_', starting with a letter or '_'");
    std::string shadowed;
    if (name == "x" || name == "y") shadowed = "the variable " + name;
    if (name == "pi" || name == "e") shadowed = "the constant " + name;
    if (find_function(name)) shadowed = "the function " + name;
    if (find_non_smooth(name)) shadowed = "the reserved name " + name;
    if (!shadowed.empty()) throw InputError("param " + quoted(name) + " shadows " + shadowed + "; rename it");
    if (!std::isfinite(value)) throw InputError("param " + quoted(name) + " is not finite");
  }
}

}  // namespace

Formula::Formula() : text_("0"), program_{Op{OpCode::push_const, 0, 0.0}}, max_stack_(1) {}

Formula Formula::parse(std::string_view text, const std::map<std::string, double>& params) {
  if (text.size() > kMaxLength)
    throw InputError("formula is " + std::to_string(text.size()) + " characters long; the limit is " +
                         std::to_string(kMaxLength),
                     "", static_cast<int>(kMaxLength + 1));
  if (text.find_first_not_of(kSpace) == std::string_view::npos) throw InputError("empty formula", "", 1);
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
  return f;
}

}  // namespace rb

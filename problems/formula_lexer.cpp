// The formula lexer (formula_lexer.hpp).
#include "problems/formula_lexer.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>

#include "problems/input_error.hpp"

namespace rb::formula_detail {
namespace {

constexpr std::string_view kPunctuation = "+-*/^(),";
constexpr std::array<Tok, 8> kPunctuationTok = {Tok::plus,  Tok::minus,  Tok::star,   Tok::slash,
                                                Tok::power, Tok::lparen, Tok::rparen, Tok::comma};

}  // namespace

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }

bool is_name(std::string_view s) {
  return !s.empty() && is_name_start(s[0]) && std::all_of(s.begin(), s.end(), is_name_char);
}

std::string quoted(std::string_view s) {
  constexpr std::size_t kShown = 32;
  // appended piece by piece: "'" + std::string(...) trips GCC 12's false
  // -Wrestrict on the inlined insert (GCC bug 105329)
  std::string out = "'";
  out.append(s.substr(0, kShown));
  if (s.size() > kShown) out.append("...");
  out.push_back('\'');
  return out;
}

std::string Lexer::describe(const Token& t) const {
  return t.kind == Tok::end ? "the end of the formula" : quoted(spelling(t));
}

void Lexer::fail(const std::string& message, std::size_t pos) {
  throw InputError(message, "", static_cast<int>(pos + 1));
}

void Lexer::advance() {
  prev_ = tok_;
  tok_ = lex();
}

Token Lexer::lex() {
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

void Lexer::unexpected_character(std::size_t at) const {
  const auto byte = static_cast<unsigned char>(text_[at]);
  if (byte >= 0x20 && byte < 0x7f) fail("unexpected character '" + std::string(1, text_[at]) + "'", at);
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X", byte);
  if (byte >= 0x80)
    fail(std::string("unexpected non-ASCII character (byte ") + hex + "); formulas are plain ASCII", at);
  fail(std::string("unexpected control character (byte ") + hex + ")", at);
}

// digits [. digits] [(e|E) [+|-] digits], or . digits
Token Lexer::lex_number() {
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

}  // namespace rb::formula_detail

#pragma once
// The formula language's tokens (docs/formats.md, "Formula language"): numbers,
// names, the operators + - * / ^ ** and ( ) ,. Internal to the parser
// (formula_parser.cpp); errors are InputErrors with the 1-based column.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

namespace rb::formula_detail {

bool is_digit(char c);
bool is_name_start(char c);
bool is_name_char(char c);
// letters, digits and '_', not starting with a digit
bool is_name(std::string_view s);

// A name or number quoted for a message, cut short so that a hostile
// formula cannot make a huge message.
std::string quoted(std::string_view s);

inline constexpr std::string_view kSpace = " \t\r\n";

enum class Tok { number, name, plus, minus, star, slash, power, lparen, rparen, comma, end };

struct Token {
  Tok kind = Tok::end;
  std::size_t pos = 0, len = 0;  // where in the text
  double number = 0.0;           // the value of a number
};

// Reads the text one token at a time.
class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {}

  // Moves to the next token; throws InputError at a character or number
  // that is not in the language.
  void advance();
  const Token& token() const { return tok_; }
  // The token before the current one (len 0 before the first).
  const Token& previous() const { return prev_; }

  std::string_view spelling(const Token& t) const { return text_.substr(t.pos, t.len); }
  // The token for a message: quoted, or "the end of the formula".
  std::string describe(const Token& t) const;

  // Throws InputError with the message at 0-based position pos.
  [[noreturn]] static void fail(const std::string& message, std::size_t pos);

 private:
  Token lex();
  Token lex_number();
  bool at_digit(std::size_t i) const { return i < text_.size() && is_digit(text_[i]); }
  [[noreturn]] void unexpected_character(std::size_t at) const;

  std::string_view text_;
  std::size_t pos_ = 0;
  Token tok_, prev_;
};

}  // namespace rb::formula_detail

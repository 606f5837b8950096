#include "problems/safe_name.hpp"

#include <cstdio>

#include "problems/input_error.hpp"

namespace rb {

namespace {

bool is_safe_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
}

}  // namespace

std::string escaped_excerpt(const std::string& text, std::size_t max_length) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_length; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (text.size() > max_length) out += "...";
  return out;
}

const std::string& check_safe_name(const std::string& name, const std::string& key) {
  const std::string rule = " (a name takes 1 to " + std::to_string(kMaxSafeNameLength) +
                           " letters, digits, '-', '_' or '.', not starting with '.')";
  if (name.empty()) throw InputError("must not be empty" + rule, key);
  if (name.size() > kMaxSafeNameLength)
    throw InputError("is " + std::to_string(name.size()) + " characters long" + rule, key);
  if (name.front() == '.') throw InputError("'" + escaped_excerpt(name) + "' starts with '.'" + rule, key);
  for (std::size_t i = 0; i < name.size(); ++i)
    if (!is_safe_char(name[i]))
      throw InputError("'" + escaped_excerpt(name) + "' holds '" + escaped_excerpt(name.substr(i, 1)) +
                           "' at character " + std::to_string(i + 1) + rule,
                       key);
  return name;
}

}  // namespace rb

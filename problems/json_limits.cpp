#include "problems/json_limits.hpp"

#include "problems/safe_name.hpp"

namespace rb {

std::size_t json_too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string_view::npos;
}

std::string json_error_text(const std::string& what) {
  std::string text = what;
  if (text.rfind("[json.exception.", 0) == 0)
    if (const auto p = text.find("] "); p != std::string::npos) text = text.substr(p + 2);
  const std::string marker = "; last read: '";
  const auto at = text.find(marker);
  if (at == std::string::npos) return text;
  // the token ends at the last quote, before nlohmann's "; expected ..." if any
  const std::size_t from = at + marker.size();
  std::size_t end = text.rfind("'; expected ");
  if (end == std::string::npos || end < from) end = text.size() - (text.back() == '\'' ? 1 : 0);
  const std::string rest = end < text.size() ? text.substr(end + 1) : "";
  return text.substr(0, at) + marker + escaped_excerpt(text.substr(from, end - from)) + "'" + rest;
}

}  // namespace rb

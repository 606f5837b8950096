#include "bench/lib/json_input.hpp"

#include "problems/input_error.hpp"

namespace rb {

nlohmann::json parse_limited_json(const std::string& text, const std::string& what, const std::string& path,
                                  const std::string& key) {
  const std::string name = "the " + what + " '" + shown_path(path) + "'";
  // before parsing: no parser, destructor or dump then recurses on it
  if (const std::size_t at = json_too_deep_at(text); at != std::string::npos)
    throw InputError(name + " nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                         std::to_string(at + 1) + ")",
                     key);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name + " is not JSON (syntax error at byte " + std::to_string(e.byte) + ")", key);
  } catch (const nlohmann::json::out_of_range&) {
    // 1e400: a number beyond double's range
    throw InputError(name + " holds a number out of range", key);
  } catch (const nlohmann::json::exception&) {
    throw InputError(name + " is not JSON", key);
  }
}

nlohmann::json read_json_file(const std::string& path, const InputKind& kind, const std::string& key) {
  return parse_limited_json(read_input_file(path, kind, key), kind.name, path, key);
}

}  // namespace rb

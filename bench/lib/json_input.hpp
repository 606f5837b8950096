#pragma once
// Every JSON file rollbench reads from the command line (reports and shards,
// peer files, cached references) is read here, with limits: only a regular
// file of at most kMaxJsonBytes, nested at most kMaxJsonDepth deep, numbers
// within double's range. Anything else is an InputError under the key that
// names the file's option; the message gives the place (a byte offset) and
// never quotes the file's content.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace rb {

inline constexpr std::size_t kMaxJsonBytes = std::size_t{1} << 30;  // 1 GiB
inline constexpr int kMaxJsonDepth = 64;

// The bytes of path if it is a regular file (after symlinks) of at most
// max_bytes; InputError under key otherwise ("cannot read the WHAT 'PATH'").
std::string read_regular_file(const std::string& path, const std::string& what, const std::string& key,
                              std::size_t max_bytes);

// text parsed within the limits; errors name the WHAT 'PATH' and the key.
nlohmann::json parse_limited_json(const std::string& text, const std::string& what, const std::string& path,
                                  const std::string& key);

// read_regular_file (kMaxJsonBytes) then parse_limited_json.
nlohmann::json read_json_file(const std::string& path, const std::string& what, const std::string& key);

}  // namespace rb

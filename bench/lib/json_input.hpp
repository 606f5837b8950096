#pragma once
// Every JSON file rollbench reads from the command line (reports and shards,
// peer files, cached references) is read here, with limits: a regular file
// of at most its kind's size (problems/input_file.hpp), nested at most
// kMaxJsonDepth deep, numbers within double's range. Anything else is an
// InputError under the key that names the file's option; the message gives
// the place (a byte offset) and never quotes the file's content.
#include <nlohmann/json.hpp>
#include <string>

#include "problems/input_file.hpp"
#include "problems/json_limits.hpp"

namespace rb {

// text parsed within the limits; errors name the WHAT 'PATH' and the key.
nlohmann::json parse_limited_json(const std::string& text, const std::string& what, const std::string& path,
                                  const std::string& key);

// read_input_file then parse_limited_json, both naming the file as kind.name.
nlohmann::json read_json_file(const std::string& path, const InputKind& kind, const std::string& key);

}  // namespace rb

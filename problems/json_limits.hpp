#pragma once
// The limits every JSON input is parsed within, checked before the parser
// builds anything: how deep it nests, and what of it a message may quote.
#include <cstddef>
#include <string>
#include <string_view>

namespace rb {

// No rollbench file nests deeper than 6 levels; 100 000 '[' would overflow
// the stack of any recursive walk (dump, a destructor, a comparison).
inline constexpr int kMaxJsonDepth = 64;

// The byte offset of the first '[' or '{' nested deeper than max_depth
// (strings skipped), or npos: a linear scan that allocates nothing.
std::size_t json_too_deep_at(std::string_view text, int max_depth = kMaxJsonDepth);

// nlohmann's what() as a message may show it: without its
// "[json.exception.parse_error.101] " prefix, and the token it quotes after
// "last read: " (any length of the file's bytes) cut to a short escaped excerpt.
std::string json_error_text(const std::string& what);

}  // namespace rb

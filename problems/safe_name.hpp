#pragma once
// Names that come from input and may become part of a file name (a scene's
// "name", for one) are names, never paths: checked once, where they are read.
#include <cstddef>
#include <string>

namespace rb {

// The safe set: 1 to kMaxSafeNameLength characters, each an ASCII letter,
// digit, '-', '_' or '.', not starting with '.' (so neither "..", a hidden
// file nor a path separator or NUL can get through).
inline constexpr std::size_t kMaxSafeNameLength = 64;

// Throws InputError under key naming what is wrong; returns name otherwise.
const std::string& check_safe_name(const std::string& name, const std::string& key);

// The name with anything outside printable ASCII escaped (\xNN) and cut to
// max_length characters: what an error message may quote of input.
std::string escaped_excerpt(const std::string& text, std::size_t max_length = 40);

}  // namespace rb

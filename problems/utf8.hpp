#pragma once
// Text from outside the suite (a plug-in's messages and facts, a path the
// user typed, an exception's what()) may hold any bytes; JSON needs UTF-8.
// valid_utf8 is the one place where such text is made valid, so every
// output (report, score, stderr) shows the same characters for it.
#include <string>
#include <string_view>

namespace rb {

// text with every byte that does not begin a well-formed UTF-8 sequence
// (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF)
// replaced by U+FFFD; valid text is returned unchanged.
std::string valid_utf8(std::string_view text);

}  // namespace rb

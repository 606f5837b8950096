// valid_utf8 (problems/utf8.hpp): valid text passes unchanged, and each
// byte that does not begin a well-formed sequence becomes one U+FFFD.
#include <gtest/gtest.h>

#include <vector>

#include "problems/utf8.hpp"

namespace rb {
namespace {

const std::string kReplacement = "\xEF\xBF\xBD";

std::string replaced(int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += kReplacement;
  return out;
}

TEST(Utf8, ValidTextPassesUnchanged) {
  for (const std::string& text :
       std::vector<std::string>{"", "plain ASCII", "caf\xC3\xA9", "\xE2\x82\xAC 5", "\xF0\x9F\x98\x80", "\xED\x9F\xBF",
                                "\xF4\x8F\xBF\xBF", kReplacement})
    EXPECT_EQ(valid_utf8(text), text);
  EXPECT_EQ(valid_utf8(std::string("a\0b", 3)), std::string("a\0b", 3));
}

TEST(Utf8, EachBadByteIsOneReplacementCharacter) {
  EXPECT_EQ(valid_utf8("bad \xFF\xFE here"), "bad " + replaced(2) + " here");
  EXPECT_EQ(valid_utf8("\xC0\xAF"), replaced(2));          // overlong '/'
  EXPECT_EQ(valid_utf8("\xE0\x80\xAF"), replaced(3));      // overlong, three bytes
  EXPECT_EQ(valid_utf8("\xED\xA0\x80"), replaced(3));      // a UTF-16 surrogate
  EXPECT_EQ(valid_utf8("\xF4\x90\x80\x80"), replaced(4));  // above U+10FFFF
  EXPECT_EQ(valid_utf8("\xE2\x82"), replaced(2));          // cut short at the end
  EXPECT_EQ(valid_utf8("\xE2\x82x"), replaced(2) + "x");   // cut short before ASCII
  EXPECT_EQ(valid_utf8("\x80 lone continuation"), kReplacement + " lone continuation");
  EXPECT_EQ(valid_utf8("\xC3\xA9\xFF\xC3\xA9"), "\xC3\xA9" + kReplacement + "\xC3\xA9");
}

}  // namespace
}  // namespace rb

// issue 32: names that would be paths, JSON past its limits and shard indices
// of the wrong type are refused with exit 2 and the key, never obeyed.
#include <gtest/gtest.h>

#include <string>

#include "bench/lib/json_input.hpp"
#include "bench/lib/report.hpp"
#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"

namespace rb {
namespace {

std::string refusal(const std::string& name) {
  try {
    check_safe_name(name, "name");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileInput, ANameThatWouldBeAPathIsRefusedNamingTheKey) {
  const std::string rule = " (a name takes 1 to 64 letters, digits, '-', '_' or '.', not starting with '.')";
  EXPECT_EQ(refusal("../../../../../etc/x"), "'name': '../../../../../etc/x' starts with '.'" + rule);
  EXPECT_EQ(refusal(std::string("victim\0", 7)), "'name': 'victim\\x00' holds '\\x00' at character 7" + rule);
  EXPECT_EQ(refusal("a/b"), "'name': 'a/b' holds '/' at character 2" + rule);
  EXPECT_EQ(refusal(".hidden"), "'name': '.hidden' starts with '.'" + rule);
  EXPECT_EQ(refusal(""), "'name': must not be empty" + rule);
  EXPECT_EQ(refusal(std::string(65, 'a')), "'name': is 65 characters long" + rule);
  EXPECT_EQ(refusal(std::string(64, 'a')), "");
  EXPECT_EQ(refusal("bowl-3d_v1.2"), "");
}

std::string parse_refusal(const std::string& text) {
  try {
    parse_limited_json(text, "report", "s.json", "report");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileInput, JsonPastItsLimitsIsAnInputError) {
  EXPECT_EQ(parse_refusal(std::string(100000, '[')),
            "'report': the report 's.json' nests deeper than 64 levels (at byte 65)");
  EXPECT_EQ(parse_refusal(std::string(64, '[') + std::string(64, ']')), "");
  EXPECT_EQ(parse_refusal("[\"[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\"]"), "");
  EXPECT_EQ(parse_refusal("{\"index\": 1e400}"), "'report': the report 's.json' holds a number out of range");
  // the syntax error gives a place, never the file's text
  EXPECT_EQ(parse_refusal("secret-content"), "'report': the report 's.json' is not JSON (syntax error at byte 1)");
}

std::string merge_refusal(const nlohmann::json& shard) {
  try {
    merge_reports({shard}, {"s.json"});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileInput, AShardIndexOfTheWrongTypeNamesTheKey) {
  const std::string want =
      "'options.shard': 's.json': must be [index, count], whole numbers with 0 <= index < count <= 1000000";
  EXPECT_EQ(merge_refusal({{"options", {{"shard", {1e300, 1}}}}}), want);
  EXPECT_EQ(merge_refusal({{"options", {{"shard", {0.5, 1}}}}}), want);
  EXPECT_EQ(merge_refusal({{"options", {{"shard", {-1, 1}}}}}), want);
  EXPECT_EQ(merge_refusal({{"options", {{"shard", {"0", 1}}}}}),
            "'options.shard': 's.json': must be [index, count], two whole numbers");
  EXPECT_EQ(merge_refusal({{"options", 1}}), "'options.shard': 's.json': is missing");
}

}  // namespace
}  // namespace rb

// The formula language's names have one list (formula_parser.cpp) and one
// way to refuse a param that shadows any of them, in formulas and in scenes
// alike: the same key and the same sentence for every reserved name.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "problems/formula.hpp"
#include "problems/scene.hpp"

namespace rb {
namespace {

const std::string kShadowTail =
    " shadows a name of the formula language (x y pi e sin cos tan asin acos atan sinh cosh tanh exp log "
    "sqrt atan2 hypot abs min max sign floor ceil round); rename it";

std::string scene_with_param(const std::string& name) {
  return R"({"name": "t", "landscape": "x^2/10", "params": {")" + name +
         R"(": 1}, "ball": {"radius": 0.1, "mass": 1}, "start": {"contact": [0, 0], "omega": [0, 0, 0]}, "t_end": 1})";
}

TEST(FormulaVocabulary, ListsVariablesConstantsFunctionsAndRejectedNames) {
  const std::vector<std::string_view> names = formula_reserved_names();
  EXPECT_EQ(names.size(), 25u);
  for (const char* name : {"x", "y", "pi", "e", "sin", "hypot", "atan2", "abs", "sign", "floor", "ceil", "round"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(FormulaVocabulary, EveryReservedNameIsKnownToTheParser) {
  // each name either works in a formula or is refused for what it is, never
  // as an unknown name: the list and the parser are the same tables
  for (const std::string_view name : formula_reserved_names()) {
    for (const std::string& text : {std::string(name), std::string(name) + "(x)", std::string(name) + "(x, y)"}) {
      try {
        Formula::parse(text);
      } catch (const InputError& e) {
        EXPECT_EQ(e.message().find("unknown"), std::string::npos) << text << ": " << e.message();
      }
    }
  }
}

TEST(FormulaVocabulary, AFormulaParamThatShadowsAnyNameIsRefusedInOneSentence) {
  for (const std::string_view name : formula_reserved_names()) {
    try {
      Formula::parse("1", {{std::string(name), 1.0}});
      ADD_FAILURE() << "param " << name << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.message(), "param '" + std::string(name) + "'" + kShadowTail);
      EXPECT_EQ(e.key(), "");
      EXPECT_EQ(e.column(), 0);
    }
  }
}

TEST(FormulaVocabulary, ASceneParamThatShadowsAnyNameIsRefusedUnderItsKey) {
  for (const std::string_view name : formula_reserved_names()) {
    try {
      parse_scene(scene_with_param(std::string(name)));
      ADD_FAILURE() << "param " << name << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "params." + std::string(name));
      EXPECT_EQ(e.message(), "param '" + std::string(name) + "'" + kShadowTail);
    }
  }
}

TEST(FormulaVocabulary, ParamNamesThatAreNotNamesAreRefusedTheSameWayEverywhere) {
  const std::string message =
      "param name 'a b' is not a name: use letters, digits and '_', starting with a letter or '_'";
  try {
    check_formula_param_name("a b");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), message);
  }
  try {
    parse_scene(scene_with_param("a b"));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "params.a b");
    EXPECT_EQ(e.message(), message);
  }
  EXPECT_NO_THROW(check_formula_param_name("_a1"));
  EXPECT_NO_THROW(check_formula_param_name("sine"));
}

}  // namespace
}  // namespace rb

// docs/bad-input.md, the catalogue of bad input and failures, names the test
// that proves each entry as `tests/<file>.cpp: Suite.Name`. These tests keep
// it from rotting: every named test exists in the named file, every run
// status is catalogued, and every robustness test is cited.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "problems/status.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string& catalogue() {
  static const std::string text = read_text(fs::path(RB_SOURCE_DIR) / "docs" / "bad-input.md");
  return text;
}

struct Citation {
  std::string file, suite, name;
};

std::vector<Citation> citations() {
  static const std::regex cite(R"((tests/[A-Za-z0-9_/.-]+\.cpp): ([A-Za-z_][A-Za-z0-9_]*)\.([A-Za-z_][A-Za-z0-9_]*))");
  std::vector<Citation> out;
  const std::string& text = catalogue();
  for (auto it = std::sregex_iterator(text.begin(), text.end(), cite); it != std::sregex_iterator(); ++it)
    out.push_back({(*it)[1], (*it)[2], (*it)[3]});
  return out;
}

// TEST(Suite, Name), TEST_F(...) or TEST_P(...) in the source text
bool defines(const std::string& source, const std::string& suite, const std::string& name) {
  const std::regex test("TEST(_F|_P)?\\(\\s*" + suite + "\\s*,\\s*" + name + "\\s*\\)");
  return std::regex_search(source, test);
}

TEST(Catalogue, EveryCitedTestExistsInItsFile) {
  ASSERT_FALSE(catalogue().empty()) << "docs/bad-input.md is missing";
  const std::vector<Citation> cited = citations();
  EXPECT_GE(cited.size(), 40u) << "the catalogue cites too few tests: is the citation format intact?";
  for (const Citation& c : cited) {
    const fs::path file = fs::path(RB_SOURCE_DIR) / c.file;
    ASSERT_TRUE(fs::exists(file)) << c.file << " (cited for " << c.suite << "." << c.name << ")";
    EXPECT_TRUE(defines(read_text(file), c.suite, c.name)) << c.file << " has no test " << c.suite << "." << c.name;
  }
}

TEST(Catalogue, EveryRunStatusIsCatalogued) {
  for (const Status s :
       {Status::ok, Status::diverged, Status::lift_off, Status::curvature, Status::domain, Status::step_underflow,
        Status::max_steps, Status::crashed, Status::timeout, Status::off_group, Status::solver, Status::error}) {
    const std::string entry = "| `" + std::string(status_name(s)) + "` |";
    EXPECT_NE(catalogue().find(entry), std::string::npos) << "no catalogue row for the status " << status_name(s);
  }
}

TEST(Catalogue, EveryRobustnessTestIsCited) {
  std::set<std::string> cited;
  for (const Citation& c : citations()) cited.insert(c.suite + "." + c.name);
  static const std::regex test(R"(TEST(_F|_P)?\(\s*([A-Za-z0-9_]+)\s*,\s*([A-Za-z0-9_]+)\s*\))");
  for (const auto& entry : fs::directory_iterator(fs::path(RB_SOURCE_DIR) / "tests" / "robustness")) {
    if (entry.path().extension() != ".cpp" || entry.path().filename() == "test_catalogue.cpp") continue;
    const std::string source = read_text(entry.path());
    for (auto it = std::sregex_iterator(source.begin(), source.end(), test); it != std::sregex_iterator(); ++it)
      EXPECT_TRUE(cited.count(std::string((*it)[2]) + "." + std::string((*it)[3])))
          << entry.path().filename().string() << ": " << (*it)[2] << "." << (*it)[3] << " is not in docs/bad-input.md";
  }
}

}  // namespace
}  // namespace rb

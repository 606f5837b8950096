// Native landscapes (problems/formula_native.hpp): the compiled code gives
// the tape's bits on the test formulas and the fuzz corpus, the cache
// rebuilds corrupted, truncated and stale entries instead of loading them,
// and without a compiler the tape runs.
#include <gtest/gtest.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "problems/formula.hpp"
#include "problems/formula_codegen.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;

// RB_NATIVE_FORMULA=off is the run without native code: these tests then
// have nothing to test (the rest of the suite runs on the tape)
bool native_switched_off() { return !NativeSettings::from_environment().enabled; }

#define SKIP_IF_SWITCHED_OFF() \
  if (native_switched_off()) GTEST_SKIP() << "RB_NATIVE_FORMULA=off"

// a cache folder of this test alone, removed at the end
class TempCache {
 public:
  explicit TempCache(const std::string& name)
      : dir_(fs::temp_directory_path() / ("rb_native_" + name + "_" + std::to_string(getpid()))) {
    fs::remove_all(dir_);
  }
  ~TempCache() { fs::remove_all(dir_); }
  NativeSettings settings() const {
    NativeSettings s;
    s.cache_dir = dir_.string();
    return s;
  }
  std::vector<fs::path> entries() const {
    std::vector<fs::path> out;
    if (fs::exists(dir_))
      for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path());
    return out;
  }
  const fs::path& dir() const { return dir_; }
  // the one cache entry, f<hash>.so
  fs::path entry() const {
    for (const fs::path& p : entries())
      if (p.extension() == ".so") return p;
    return {};
  }

 private:
  fs::path dir_;
};

// the shared cache, so the agreement tests build each formula once per machine
NativeSettings shared_cache() {
  NativeSettings s = NativeSettings::from_environment();
  s.enabled = true;
  return s;
}

bool same_bits(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_jets(const Jet2<double>& a, const Jet2<double>& b, const std::string& where) {
  const double pa[6] = {a.f, a.fx, a.fy, a.fxx, a.fxy, a.fyy}, pb[6] = {b.f, b.fx, b.fy, b.fxx, b.fxy, b.fyy};
  for (int i = 0; i < 6; ++i)
    EXPECT_TRUE(same_bits(pa[i], pb[i])) << where << " part " << i << ": " << pa[i] << " vs " << pb[i];
}

// native against tape, eval and slopes, at points inside and far outside
// the landscapes' range; the number of jets compared (0 for a formula the
// tape cannot hold: the stack machine's formulas have no native path)
int expect_native_equals_tape(const std::string& text, const std::map<std::string, double>& params) {
  Formula tape = Formula::parse(text, params);
  if (!tape.tape().usable()) return 0;
  Formula native = tape;
  EXPECT_NE(native.compile_native(shared_cache()), NativeOutcome::unavailable) << text;
  if (!native.is_native()) {
    ADD_FAILURE() << "no native code for " << text;
    return 0;
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double points[][2] = {{0.0, 0.0},       {0.3, -0.7}, {-3.1, 2.4},
                              {1e-300, -1e300}, {inf, 0.5},  {-0.25, std::nan("")}};
  int compared = 0;
  for (const auto& p : points) {
    const std::string where = text + " at (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ")";
    expect_same_jets(native.eval(p[0], p[1]), tape.eval(p[0], p[1]), where + " eval");
    expect_same_jets(native.slopes(p[0], p[1]), tape.slopes(p[0], p[1]), where + " slopes");
    compared += 2;
  }
  return compared;
}

TEST(FormulaNative, AgreesWithTheTapeBitForBitOnTheTestFormulas) {
  SKIP_IF_SWITCHED_OFF();
  const std::map<std::string, double> params = {{"a", 0.5}, {"b", -2.0}};
  for (const char* text :
       {"0.05*sin(2*x)*cos(3*y) + 0.1*x^2", "0.5*y^2 + 0.05*x^2", "x", "3", "a*exp(-(x^2 + y^2)) + b*log(1 + x^2)",
        "sqrt(1 + x^2 + y^2) - hypot(x, 2)", "atan2(y, x + 3) + tan(x/4) + asin(y/9) + acos(x/9) + atan(x*y)",
        "sinh(x/3)*cosh(y/3) + tanh(x - y) + x^-2 + 2^x + x^1.5 + (x^2+1)^y", "-(x - y)/(1 + x^2) - 2/(3 + y^2)",
        "cos(x)*sin(x) + sin(y)^2"})
    EXPECT_EQ(expect_native_equals_tape(text, params), 12) << text;
}

TEST(FormulaNative, AgreesWithTheTapeBitForBitOnTheFuzzCorpus) {
  SKIP_IF_SWITCHED_OFF();
  const std::map<std::string, double> params = {{"a", 0.5}, {"b", -2.0}, {"big", 1e300}};
  int formulas = 0, jets = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RB_SOURCE_DIR) / "fuzz" / "corpus" / "fuzz_formula")) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    try {
      Formula::parse(text.str(), params);
    } catch (const InputError&) {
      continue;  // the corpus holds bad formulas too
    }
    const int compared = expect_native_equals_tape(text.str(), params);
    jets += compared;
    formulas += compared > 0;
  }
  // counted where native code was compared with the tape, not where a formula parsed
  EXPECT_GE(formulas, 10) << "the corpus should hold formulas that run as native code";
  EXPECT_EQ(jets, 12 * formulas);
}

TEST(FormulaNative, GeneratedSourceHoldsNoTextOfTheFormula) {
  const Formula f = Formula::parse("evil_name*sin(x) + other_name", {{"evil_name", 2.0}, {"other_name", 1.0}});
  const std::string source = formula_c_source(f.tape());
  EXPECT_EQ(source.find("evil_name"), std::string::npos);
  EXPECT_EQ(source.find("other_name"), std::string::npos);
  EXPECT_NE(source.find("rb_formula_slopes"), std::string::npos);
}

TEST(FormulaNative, BuildsOnceThenLoadsFromTheCache) {
  SKIP_IF_SWITCHED_OFF();
  const TempCache cache("once");
  Formula f = Formula::parse("0.25*cos(x)*y^2");
  EXPECT_EQ(f.compile_native(cache.settings()), NativeOutcome::built);
  ASSERT_EQ(cache.entries().size(), 2u);  // the entry and the secret: no temporary files left behind
  EXPECT_FALSE(cache.entry().empty());
  Formula again = Formula::parse("0.25*cos(x)*y^2");
  EXPECT_EQ(again.compile_native(cache.settings()), NativeOutcome::cached);
  EXPECT_TRUE(again.is_native());
}

// Names created in folder (watched by inotify) while run runs; the watch
// itself is checked by a file of the test's own made afterwards.
std::vector<std::string> names_created_during(const fs::path& folder, const std::function<void()>& run) {
  const int watch = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  EXPECT_GE(watch, 0);
  EXPECT_GE(inotify_add_watch(watch, folder.c_str(), IN_CREATE | IN_MOVED_TO), 0);
  run();
  std::ofstream(folder / "made-by-the-test") << "x";
  std::vector<std::string> names;
  alignas(inotify_event) char buf[8192];
  for (ssize_t got; (got = ::read(watch, buf, sizeof buf)) > 0;)
    for (char* at = buf; at < buf + got;) {
      const auto* event = reinterpret_cast<const inotify_event*>(at);
      if (event->len > 0) names.emplace_back(event->name);
      at += sizeof(inotify_event) + event->len;
    }
  ::close(watch);
  return names;
}

// issue 32: the compiler's own temporaries (cc1's assembly, as's object,
// under names it opens again) go to the private work folder, not $TMPDIR:
// with TMPDIR at a fresh folder, a build creates nothing there.
TEST(FormulaNative, TheCompilersTemporariesStayInThePrivateWorkFolder) {
  SKIP_IF_SWITCHED_OFF();
  const TempCache cache("tmpdir");
  const fs::path tmpdir = fs::temp_directory_path() / ("rb_watched_tmpdir_" + std::to_string(getpid()));
  fs::remove_all(tmpdir);
  fs::create_directories(tmpdir);
  const char* old = std::getenv("TMPDIR");
  const std::string kept = old ? old : "";
  ::setenv("TMPDIR", tmpdir.c_str(), 1);
  NativeOutcome outcome = NativeOutcome::unavailable;
  const std::vector<std::string> names = names_created_during(tmpdir, [&] {
    Formula f = Formula::parse("0.5*sin(x)*cos(y)^3 + 0.125*x*y");
    outcome = f.compile_native(cache.settings());
  });
  if (old) ::setenv("TMPDIR", kept.c_str(), 1);
  else ::unsetenv("TMPDIR");
  fs::remove_all(tmpdir);
  EXPECT_EQ(outcome, NativeOutcome::built);  // the compiler ran
  EXPECT_EQ(names, std::vector<std::string>{"made-by-the-test"});
}

// a broken entry in place of a good one: rebuilt, never loaded (want:
// built; cached for the control, an undamaged copy)
void expect_rebuilt_after(const std::string& name, const std::function<void(const fs::path&)>& damage,
                          NativeOutcome want = NativeOutcome::built) {
  const TempCache cache(name);
  const std::string text = "0.1*sin(x*y) + 0.2*x";
  Formula first = Formula::parse(text);
  ASSERT_EQ(first.compile_native(cache.settings()), NativeOutcome::built);
  first.drop_native();
  const fs::path entry = cache.entry();
  ASSERT_FALSE(entry.empty());
  // the damaged copy goes to a second folder (with the first's secret, so
  // that an undamaged copy verifies): this process has loaded the first
  const TempCache other(name + "_other");
  ASSERT_EQ(mkdir(other.dir().c_str(), 0700), 0);
  fs::copy_file(cache.dir() / "hmac-secret", other.dir() / "hmac-secret");
  const fs::path copy = other.dir() / entry.filename();
  fs::copy_file(entry, copy);
  damage(copy);
  Formula f = Formula::parse(text);
  EXPECT_EQ(f.compile_native(other.settings()), want) << name;
  ASSERT_TRUE(f.is_native());
  const Formula tape = Formula::parse(text);
  expect_same_jets(f.eval(0.4, -1.3), tape.eval(0.4, -1.3), name);
}

TEST(FormulaNative, LoadsAnUndamagedCopyOfAnEntry) {
  SKIP_IF_SWITCHED_OFF();
  expect_rebuilt_after(
      "undamaged", [](const fs::path&) {}, NativeOutcome::cached);
}

TEST(FormulaNative, RebuildsACorruptedEntry) {
  SKIP_IF_SWITCHED_OFF();
  expect_rebuilt_after("corrupted", [](const fs::path& p) {
    std::fstream io(p, std::ios::binary | std::ios::in | std::ios::out);
    io.seekp(static_cast<std::streamoff>(fs::file_size(p) / 2));
    io.put('\x5a').put('\x5a').put('\x5a');
  });
}

TEST(FormulaNative, RebuildsATruncatedEntry) {
  SKIP_IF_SWITCHED_OFF();
  expect_rebuilt_after("truncated", [](const fs::path& p) { fs::resize_file(p, fs::file_size(p) / 3); });
}

TEST(FormulaNative, RebuildsAStaleEntryForAnotherFormula) {
  SKIP_IF_SWITCHED_OFF();
  // a whole, valid entry of another formula under this formula's name
  expect_rebuilt_after("stale", [](const fs::path& p) {
    const TempCache third("stale_source");
    Formula other = Formula::parse("x^3 - y");
    ASSERT_EQ(other.compile_native(third.settings()), NativeOutcome::built);
    fs::copy_file(third.entry(), p, fs::copy_options::overwrite_existing);
  });
}

TEST(FormulaNative, WithoutACompilerTheTapeRuns) {
  const TempCache cache("no_compiler");
  NativeSettings s = cache.settings();
  s.compiler = "/nonexistent/rb-cc";
  Formula f = Formula::parse("x^2 + y");
  EXPECT_EQ(f.compile_native(s), NativeOutcome::unavailable);
  EXPECT_FALSE(f.is_native());
  EXPECT_EQ(f.eval(3.0, 1.0).f, 10.0);
  s.compiler = "false";  // runs, but compiles nothing
  EXPECT_EQ(f.compile_native(s), NativeOutcome::unavailable);
  s.enabled = false;
  EXPECT_EQ(f.compile_native(s), NativeOutcome::disabled);
  EXPECT_EQ(f.slopes(3.0, 1.0).fx, 6.0);
}

// the one line names the evaluator that runs: for a formula too deep for the
// tape that is the stack interpreter (d44d9b5 said "tape")
TEST(FormulaNative, AFormulaTooBigForTheTapeSaysTheStackInterpreterRuns) {
  std::string sum = "x";
  for (int i = 0; i < 20; ++i) sum = (i % 2 ? "x+(" : "y+(") + sum + ")";
  const std::string text = "0.01*(" + sum + ")";
  const Formula f = Formula::parse(text);
  ASSERT_FALSE(f.tape().usable()) << "stack depth " << f.stack_depth();
  const fs::path scene = testing::cli_temp_file("deep.json"), csv = testing::cli_temp_file("deep.csv");
  std::ofstream(scene) << R"({"name": "deep", "description": "a plane written too deep for the tape", "landscape": ")"
                       << text << R"(", "domain": [-1, 1, -1, 1], "ball": {"radius": 0.1, "mass": 1.0},)"
                       << R"( "start": {"contact": [0, 0], "omega": [0, 0, 0]}, "t_end": 1})";
  const testing::CliOutcome o = testing::run_rollbench(
      "trajectory " + scene.string() + " --integrator rk4 --h 0.01 --t-end 0.1 --dt-out 0.1 --out " + csv.string());
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err,
            "rollbench: a landscape formula runs on the stack interpreter, neither on the tape nor as native "
            "code (it is too long or too deep for the tape: " +
                std::to_string(f.size()) + " instructions, stack depth " + std::to_string(f.stack_depth()) + ")\n");
  fs::remove(scene);
  fs::remove(csv);
}

}  // namespace
}  // namespace rb

// Limits that protect the machine (docs/bad-input.md): input that would exhaust the
// stack, memory, disk or time, or that carries NaN or infinity, is refused
// up front with a message that has the numbers, or ends a run with a status;
// never a crash, a hang or a silent default. docs/bad-input.md lists these.
#include <cmath>
#include <limits>

#include "bench/lib/trajectory_csv.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb::robustness {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

// --- formulas ---

TEST(Limits, FormulaLengthIsCappedBeforeParsing) {
  const std::string longest = repeat("x+", Formula::kMaxLength / 2 - 1) + "yy";
  ASSERT_EQ(longest.size(), Formula::kMaxLength);
  EXPECT_THROW(Formula::parse(longest), InputError);  // "yy" is an unknown name: parsed to the end
  try {
    Formula::parse(longest + "+");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "formula is 65537 characters long; the limit is 65536");
    EXPECT_EQ(e.column(), 65537);
  }
  // the same through a scene: the key and the column
  const InputError e = scene_error(replaced(base_scene_text(), "a*x^2 - y/10", repeat("x", 70000)));
  EXPECT_EQ(e.key(), "landscape");
  EXPECT_EQ(e.message(), "formula is 70000 characters long; the limit is 65536");
}

TEST(Limits, FormulaNestingIsCappedAtTwoHundredLevels) {
  const std::string deepest = std::string(200, '(') + "x" + std::string(200, ')');
  EXPECT_EQ(Formula::parse(deepest).value(0.5, 0.0), 0.5);
  for (const std::string& text : {std::string(201, '(') + "x" + std::string(201, ')'), repeat("-", 201) + "x",
                                  repeat("exp(", 201) + "x" + std::string(201, ')'), repeat("x^", 201) + "x"}) {
    try {
      Formula::parse(text);
      ADD_FAILURE() << text.substr(0, 20);
    } catch (const InputError& e) {
      EXPECT_EQ(e.message(), "formula nests deeper than 200 levels") << text.substr(0, 20);
      EXPECT_GT(e.column(), 0);
    }
  }
  const InputError e = scene_error(replaced(base_scene_text(), "a*x^2 - y/10", repeat("sin(", 300) + "x"));
  EXPECT_EQ(e.key(), "landscape");
  EXPECT_EQ(e.column(), 804);  // the 201st opening parenthesis
}

TEST(Limits, FormulaConstantsThatOverflowAreErrorsOrNonFiniteStarts) {
  try {
    Formula::parse("x + 1e400");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "number '1e400' is out of range for a double");
    EXPECT_EQ(e.column(), 5);
  }
  // 1e308 * 10 folds to infinity: a formula, but no valid start on it
  const InputError e = scene_error(replaced(base_scene_text(), "a*x^2 - y/10", "1e308*10 + x"));
  EXPECT_EQ(e.key(), "start.contact");
  EXPECT_EQ(e.message(), "the landscape or its derivatives are not finite at the start contact");
}

// --- scenes: NaN and infinity anywhere ---

TEST(Limits, NonFiniteNumbersInEveryNumericKeyNameTheKey) {
  // JSON has no NaN or infinity literal; 1e400 is how one gets in
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"("a": 0.5)", R"("a": 1e400)"},
      {"[-2, 2, -2, 2]", "[-2, 1e400, -2, 2]"},
      {R"("radius": 0.1)", R"("radius": 1e400)"},
      {R"("mass": 1.0)", R"("mass": -1e400)"},
      {R"("gravity": 9.81)", R"("gravity": 1e400)"},
      {R"("contact": [0.0, 0.0])", R"("contact": [0.0, 1e400])"},
      {"[0.5, 0.0, 0.0]", "[0.5, 1e400, 0.0]"},
      {R"("spin": 0.0)", R"("spin": 1e400)"},
      {"[1, 0, 0, 0]", "[1e400, 0, 0, 0]"},
      {R"("t_end": 1.0)", R"("t_end": 1e400)"},
  };
  const std::vector<std::string> keys = {"params.a",          "domain",        "ball.radius",    "ball.mass",
                                         "gravity",           "start.contact", "start.velocity", "start.spin",
                                         "start.orientation", "t_end"};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const InputError e = scene_error(replaced(base_scene_text(), cases[i].first, cases[i].second));
    EXPECT_EQ(e.key(), keys[i]) << e.what();
    EXPECT_NE(e.message().find("is not a finite double"), std::string::npos) << e.what();
  }
  // omega, which excludes velocity
  const std::string with_omega =
      replaced(base_scene_text(), R"("velocity": [0.5, 0.0, 0.0], "spin": 0.0)", R"("omega": [0, 1e999, 0])");
  EXPECT_EQ(scene_error(with_omega).key(), "start.omega");
  // NaN and Infinity are not JSON
  for (const char* literal : {"NaN", "Infinity", "-Infinity", "nan"}) {
    const InputError e =
        scene_error(replaced(base_scene_text(), R"("t_end": 1.0)", R"("t_end": )" + std::string(literal)));
    EXPECT_EQ(e.key(), "");
    EXPECT_NE(e.message().find("invalid JSON at byte"), std::string::npos) << e.what();
  }
}

// JSON nests without limit; the scene reader must not recurse per level
// (the C stack is 8 MiB, and a file of 200000 brackets is 400 kB).
TEST(Limits, DeeplyNestedJsonIsAnErrorNotAStackOverflow) {
  const std::size_t depth = 200000;
  // refused before parsing, at the 65th level: no parse, dump or destructor recurses that deep
  InputError e = scene_error(std::string(depth, '[') + std::string(depth, ']'));
  EXPECT_STREQ(e.what(), "the scene nests deeper than 64 levels (at byte 65)");
  e = scene_error(repeat(R"({"a":)", depth) + "0" + std::string(depth, '}'));
  EXPECT_STREQ(e.what(), "the scene nests deeper than 64 levels (at byte 321)");
  e = scene_error(replaced(base_scene_text(), R"("a": 0.5)", R"("a": )" + std::string(depth, '[')));
  EXPECT_NE(e.message().find("the scene nests deeper than 64 levels (at byte "), std::string::npos) << e.what();
  // 64 levels parse (and are refused for what they are)
  e = scene_error(std::string(64, '[') + std::string(64, ']'));
  EXPECT_EQ(e.message(), "a scene must be a JSON object, not array");
}

TEST(Limits, FiniteButExtremeScenesAreErrorsOrRunToAStatus) {
  // a radius whose m r^2 underflows has no inertia
  EXPECT_EQ(scene_error(replaced(base_scene_text(), R"("radius": 0.1)", R"("radius": 1e-200)")).key(), "ball");
  // a start whose momentum overflows
  const InputError e = scene_error(replaced(base_scene_text(), "[0.5, 0.0, 0.0]", "[1e308, 0.0, 0.0]"));
  EXPECT_EQ(e.key(), "start");
  // a valid scene with absurd gravity loads; a run on it ends with a status
  const Problem p = make_problem(parse_scene(replaced(base_scene_text(), R"("gravity": 9.81)", R"("gravity": 1e300)")));
  for (const Integrator* m : one_per_family_and_driver()) {
    RunOptions o = options_for(*m, 0.5, 0.01, 1e-6, 0.1);
    o.max_steps = 2000;
    const RunResult r = m->integrate(p, o);
    EXPECT_NE(r.status, Status::ok) << m->name();
    EXPECT_FALSE(r.message.empty()) << m->name();
    EXPECT_TRUE(r.final_state.allFinite()) << m->name();
  }
}

// --- options: steps, end times, tolerances ---

TEST(Limits, StepCountsThatOverflowStopAtTheStartWithMaxSteps) {
  const Problem p = make_problem(load_scene("plane"));
  for (const auto& m : registry()) {
    if (m->adaptive()) continue;
    for (const auto& [h, t_end] : {std::pair{1e-300, 1.0}, {5e-324, 1.0}, {1.0, 1e300}}) {
      RunOptions o;
      o.h = h;
      o.t_end = t_end;
      const RunResult r = m->integrate(p, o);
      EXPECT_EQ(status_name(r.status), "max-steps") << m->name() << " h = " << h << " t_end = " << t_end;
      EXPECT_EQ(r.message, "the step count overflows") << m->name();
      EXPECT_EQ(r.stop_time, 0.0) << m->name();
      EXPECT_EQ(r.cost.steps, 0) << m->name();
    }
  }
}

TEST(Limits, NonFiniteOrNonPositiveStepsAndEndTimesAreInputErrors) {
  const Problem p = make_problem(load_scene("plane"));
  for (const auto& m : registry()) {
    // RunOptions::t_end <= 0 (and NaN) means the problem's own t_end; an
    // infinite one is refused
    RunOptions o = options_for(*m, 1.0, 0.01, 1e-6, 0.5);
    o.t_end = kInf;
    o.output_times.clear();
    try {
      m->integrate(p, o);
      ADD_FAILURE() << m->name() << " took t_end = inf";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "t_end") << m->name();
      EXPECT_EQ(e.message(), "t_end must be a finite number > 0") << m->name();
    }
    for (const double bad : {0.0, -1.0, kNaN, kInf}) {
      if (m->adaptive() && bad == 0.0) continue;  // h = 0: the method picks its first step
      o = options_for(*m, 1.0, 0.01, 1e-6, 0.5);
      try {
        o.h = bad;  // a negative or non-finite step is refused here, where it is set (StepSize)
        m->integrate(p, o);
        ADD_FAILURE() << m->name() << " took h = " << bad;
      } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "h") << m->name();
      }
    }
    // output times out of order or beyond t_end
    for (const std::vector<double>& times : {std::vector<double>{0.5, 0.25}, {0.5, 2.0}, {kNaN}, {-0.1}}) {
      o = options_for(*m, 1.0, 0.01, 1e-6, 0.5);
      o.output_times = times;
      EXPECT_THROW(m->integrate(p, o), InputError) << m->name();
    }
  }
}

TEST(Limits, StepCountsAboveTheBudgetRunToMaxSteps) {
  // 10^12 steps do not overflow, so they run, but only up to max_steps
  const Problem p = make_problem(load_scene("plane"));
  for (const auto& m : registry()) {
    if (m->adaptive()) continue;
    RunOptions o;
    o.h = 1e-12;
    o.max_steps = 1000;
    const RunResult r = m->integrate(p, o);
    EXPECT_EQ(status_name(r.status), "max-steps") << m->name();
    EXPECT_EQ(r.message, "reached max_steps = 1000") << m->name();
    EXPECT_NEAR(r.stop_time, 1e-9, 1e-20) << m->name();
  }
}

TEST(Limits, AbsurdTolerancesAreErrorsOrStatuses) {
  // negative, NaN, infinite, both zero: refused where they enter (the
  // Tolerances every adaptive run takes), naming the option
  struct Absurd {
    double rtol, atol;
    const char* key;
    const char* message;
  };
  const char* finite = "an adaptive method needs a finite tolerance >= 0";
  for (const Absurd& a : {Absurd{-1e-6, 1e-6, "rtol", finite}, Absurd{1e-6, -1e-6, "atol", finite},
                          Absurd{kNaN, 1e-6, "rtol", finite}, Absurd{1e-6, kInf, "atol", finite},
                          Absurd{0.0, 0.0, "rtol", "an adaptive method needs rtol > 0 or atol > 0"}}) {
    try {
      (void)Tolerances(a.rtol, a.atol);
      ADD_FAILURE() << "took rtol " << a.rtol << ", atol " << a.atol;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), a.key) << a.rtol << ", " << a.atol;
      EXPECT_EQ(e.message(), a.message) << a.rtol << ", " << a.atol;
    }
  }
  const Problem p = make_problem(load_scene("valley-sideways"));
  for (const auto& m : registry()) {
    if (!m->adaptive()) continue;
    // none given: refused by every adaptive method, naming rtol
    RunOptions none = options_for(*m, 1.0, 0.0, 1e-6, 0.5);
    none.tolerances = {};
    try {
      m->integrate(p, none);
      ADD_FAILURE() << m->name() << " ran without tolerances";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "rtol") << m->name() << ": " << e.what();
      EXPECT_EQ(e.message(), "an adaptive method needs rtol > 0 or atol > 0") << m->name();
    }
    // below rounding: step-underflow at t = 0, before any evaluation
    RunResult r = m->integrate(p, options_for(*m, 1.0, 0.0, 1e-300, 0.5));
    EXPECT_EQ(status_name(r.status), "step-underflow") << m->name() << ": " << r.message;
    EXPECT_EQ(r.stop_time, 0.0) << m->name();
    EXPECT_NE(r.message.find("below the rounding"), std::string::npos) << m->name() << ": " << r.message;
    // absurdly loose: the run is bounded by its outputs and budget, and
    // reports a status (ok with a poor answer, or a stop with a reason)
    RunOptions loose = options_for(*m, 1.0, 0.0, 1e300, 0.1);
    loose.max_steps = 10000;
    r = m->integrate(p, loose);
    EXPECT_TRUE(r.status == Status::ok || !r.message.empty()) << m->name();
    EXPECT_TRUE(r.final_state.allFinite()) << m->name() << ": " << status_name(r.status);
  }
}

// --- output size ---

TEST(Limits, OutputRowsAreCappedBeforeTheRun) {
  try {
    equally_spaced_outputs(1e-9, 1.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "dt-out");
    EXPECT_EQ(e.message(), "t_end / dt-out asks for 1000000000 rows, more than the limit of 10000000");
  }
  EXPECT_EQ(equally_spaced_outputs(0.1, 1.0, 10).size(), 10u);
  EXPECT_THROW(equally_spaced_outputs(0.1, 1.0, 9), InputError);
  for (const double bad : {0.0, -1.0, kNaN, kInf}) EXPECT_THROW(equally_spaced_outputs(bad, 1.0), InputError);
}

// t_end / dt-out beyond every integer: the count must still be reported as
// a number, and a NaN end time refused, not cast to an integer (UB).
TEST(Limits, OutputRowsOfAnInfiniteOrNaNEndTimeAreRefused) {
  for (const double t_end : {1e300, kInf}) {
    try {
      equally_spaced_outputs(0.01, t_end);
      ADD_FAILURE() << t_end;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "dt-out");
      EXPECT_NE(e.message().find("more than the limit of 10000000"), std::string::npos) << e.what();
      EXPECT_EQ(e.message().find("-9223372036854775808"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(equally_spaced_outputs(0.01, kNaN), InputError);
}

TEST(Limits, TrajectoryRefusesTooManyRowsBeforeWritingAnything) {
  const auto csv = temp_path("rows.csv");
  std::filesystem::remove(csv);
  const CliOutcome o = rollbench("trajectory plane --integrator rk4 --h 0.01 --t-end 1e6 --out " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("rollbench: 'dt-out': t_end / dt-out asks for 100000000 rows, more than the limit of 10000000"),
            std::string::npos)
      << o.err;
  EXPECT_FALSE(std::filesystem::exists(csv)) << "refused before the file is opened";
}

TEST(Limits, TrajectoryWithAnOverflowingStepCountExitsThree) {
  const auto csv = temp_path("overflow.csv");
  const CliOutcome o = rollbench("trajectory plane --integrator rkmk4 --h 1e-300 --out " + csv.string());
  EXPECT_EQ(o.code, 3) << o.err;
  EXPECT_NE(o.err.find("rollbench: run stopped early at t = 0: max-steps: the step count overflows"), std::string::npos)
      << o.err;
}

TEST(Limits, TrajectoryTolerancesFromTheCommandLine) {
  const auto csv = temp_path("tol.csv");
  CliOutcome o = rollbench("trajectory plane --integrator odeint-dopri5-adaptive --rtol -1 --out " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("'rtol'"), std::string::npos) << o.err;
  o = rollbench("trajectory plane --integrator odeint-dopri5-adaptive --rtol 1e-300 --atol 1e-300 --out " +
                csv.string());
  EXPECT_EQ(o.code, 3);
  EXPECT_NE(o.err.find("step-underflow"), std::string::npos) << o.err;
}

}  // namespace
}  // namespace rb::robustness

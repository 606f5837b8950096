#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "problems/formula.hpp"
#include "problems/landscape.hpp"

namespace rb {
namespace {

using Parts = std::array<double, 6>;  // f, fx, fy, fxx, fxy, fyy
using Point = std::array<double, 2>;
constexpr double kPi = std::numbers::pi;

struct ClosedForm {
  std::string text;
  std::function<Parts(double, double)> exact;
  std::vector<Point> points = {{0.3, 0.7}, {-0.6, 0.2}, {1.1, -0.4}};
  std::map<std::string, double> params = {};
};

Parts parts(const Jet2<double>& j) { return {j.f, j.fx, j.fy, j.fxx, j.fxy, j.fyy}; }

std::vector<ClosedForm> closed_forms() {
  const std::vector<Point> positive = {{0.3, 0.7}, {1.7, 0.4}, {2.5, 1.3}};
  const std::vector<Point> unit_disc = {{0.3, 0.2}, {-0.5, 0.4}, {0.1, -0.8}};
  return {
      {"cos(x*pi + pi)/10 - y/10",
       [](double x, double y) -> Parts {
         const double c = std::cos(kPi * x), s = std::sin(kPi * x);
         return {-c / 10 - y / 10, kPi * s / 10, -0.1, kPi * kPi * c / 10, 0, 0};
       }},
      {"exp(-(x^2+y^2))",
       [](double x, double y) -> Parts {
         const double g = std::exp(-(x * x + y * y));
         return {g, -2 * x * g, -2 * y * g, (4 * x * x - 2) * g, 4 * x * y * g, (4 * y * y - 2) * g};
       }},
      {"1 - sqrt(1 - x^2 - y^2)",
       [](double x, double y) -> Parts {
         const double s = std::sqrt(1 - x * x - y * y), s3 = s * s * s;
         return {1 - s, x / s, y / s, (1 - y * y) / s3, x * y / s3, (1 - x * x) / s3};
       },
       unit_disc},
      {"atan2(y, x)",
       [](double x, double y) -> Parts {
         const double r2 = x * x + y * y, r4 = r2 * r2;
         return {std::atan2(y, x), -y / r2, x / r2, 2 * x * y / r4, (y * y - x * x) / r4, -2 * x * y / r4};
       }},
      {"hypot(x, y)",
       [](double x, double y) -> Parts {
         const double r = std::hypot(x, y), r3 = r * r * r;
         return {r, x / r, y / r, y * y / r3, -x * y / r3, x * x / r3};
       }},
      {"x^y",
       [](double x, double y) -> Parts {
         const double p = std::pow(x, y), l = std::log(x);
         return {p, y * p / x, p * l, y * (y - 1) * p / (x * x), p / x * (1 + y * l), p * l * l};
       },
       positive},
      {"2^-x",
       [](double x, double) -> Parts {
         const double p = std::pow(2.0, -x), l = std::log(2.0);
         return {p, -l * p, 0, l * l * p, 0, 0};
       }},
      {"sinh(x)*cosh(y)",
       [](double x, double y) -> Parts {
         const double sx = std::sinh(x), cx = std::cosh(x), sy = std::sinh(y), cy = std::cosh(y);
         return {sx * cy, cx * cy, sx * sy, sx * cy, cx * sy, sx * cy};
       }},
      {"tanh(x*y)",
       [](double x, double y) -> Parts {
         const double t = std::tanh(x * y), s = 1 - t * t;
         return {t, y * s, x * s, -2 * t * s * y * y, s - 2 * t * s * x * y, -2 * t * s * x * x};
       }},
      {"asin(x*y)",
       [](double x, double y) -> Parts {
         const double u = x * y, g1 = 1 / std::sqrt(1 - u * u), g2 = u * g1 * g1 * g1;
         return {std::asin(u), y * g1, x * g1, y * y * g2, g1 + x * y * g2, x * x * g2};
       },
       unit_disc},
      {"acos(x) + atan(y)",
       [](double x, double y) -> Parts {
         const double q = 1 - x * x, d = 1 + y * y;
         return {std::acos(x) + std::atan(y), -1 / std::sqrt(q), 1 / d, -x / (q * std::sqrt(q)), 0, -2 * y / (d * d)};
       },
       unit_disc},
      {"tan(x) - y",
       [](double x, double y) -> Parts {
         const double t = std::tan(x), s = 1 + t * t;
         return {t - y, s, -1, 2 * t * s, 0, 0};
       }},
      {"log(x^2 + y^2)",
       [](double x, double y) -> Parts {
         const double r2 = x * x + y * y, r4 = r2 * r2;
         return {
             std::log(r2), 2 * x / r2, 2 * y / r2, 2 * (y * y - x * x) / r4, -4 * x * y / r4, 2 * (x * x - y * y) / r4};
       }},
      {"a*x^2 + b*y",
       [](double x, double y) -> Parts { return {0.5 * x * x - 2 * y, x, -2, 1, 0, 0}; },
       {{0.3, 0.7}, {0.0, 0.0}},
       {{"a", 0.5}, {"b", -2.0}}},
      {"x**3 * y",
       [](double x, double y) -> Parts { return {x * x * x * y, 3 * x * x * y, x * x * x, 6 * x * y, 3 * x * x, 0}; }},
      // unary minus binds looser than power; integer powers are exact at 0
      {"-x^2 + y^2",
       [](double x, double y) -> Parts { return {-x * x + y * y, -2 * x, 2 * y, -2, 0, 2}; },
       {{0.0, 0.0}, {0.3, -0.7}}},
      {"x/y",
       [](double x, double y) -> Parts { return {x / y, 1 / y, -x / (y * y), 0, -1 / (y * y), 2 * x / (y * y * y)}; }},
      {"sin(x)*cos(y)",
       [](double x, double y) -> Parts {
         const double sx = std::sin(x), cx = std::cos(x), sy = std::sin(y), cy = std::cos(y);
         return {sx * cy, cx * cy, -sx * sy, -sx * cy, -cx * sy, -sx * cy};
       }},
      {"x^1.5 + y^-2",
       [](double x, double y) -> Parts {
         return {std::pow(x, 1.5) + 1 / (y * y),
                 1.5 * std::sqrt(x),
                 -2 / (y * y * y),
                 0.75 / std::sqrt(x),
                 0,
                 6 / (y * y * y * y)};
       },
       positive},
      {"sqrt(x*y)",
       [](double x, double y) -> Parts {
         const double s = std::sqrt(x * y), s3 = s * s * s;
         return {s, y / (2 * s), x / (2 * s), -y * y / (4 * s3), 1 / (4 * s), -x * x / (4 * s3)};
       },
       positive},
      {"exp(x)*log(y)",
       [](double x, double y) -> Parts {
         const double e = std::exp(x), l = std::log(y);
         return {e * l, e * l, e / y, e * l, e / y, -e / (y * y)};
       },
       positive},
      {"1/(1 + x^2 + y^2)",
       [](double x, double y) -> Parts {
         const double q = 1 / (1 + x * x + y * y), q2 = q * q, q3 = q2 * q;
         return {q, -2 * x * q2, -2 * y * q2, -2 * q2 + 8 * x * x * q3, 8 * x * y * q3, -2 * q2 + 8 * y * y * q3};
       }},
      {"sin(y)/(x + 2)",
       [](double x, double y) -> Parts {
         const double s = std::sin(y), c = std::cos(y), d = x + 2;
         return {s / d, -s / (d * d), c / d, 2 * s / (d * d * d), -c / (d * d), -s / d};
       }},
      {"2^3^2 * x", [](double x, double) -> Parts { return {512 * x, 512, 0, 0, 0, 0}; }},
      {"hypot(3, x) + atan2(1, y)",
       [](double x, double y) -> Parts {
         const double h = std::hypot(3.0, x), d = 1 + y * y;
         return {h + std::atan2(1.0, y), x / h, -1 / d, 9 / (h * h * h), 0, 2 * y / (d * d)};
       }},
      {"cosh(x - y) + e^x",
       [](double x, double y) -> Parts {
         const double s = std::sinh(x - y), c = std::cosh(x - y), e = std::exp(x);
         return {c + e, s + e, -s, c + e, -c, c};
       }},
      {"2/x - (3 - y)",
       [](double x, double y) -> Parts { return {2 / x - 3 + y, -2 / (x * x), 1, 4 / (x * x * x), 0, 0}; }},
  };
}

TEST(Formula, ValueGradientAndHessianMatchClosedForms) {
  const auto cases = closed_forms();
  ASSERT_GE(cases.size(), 20u);
  for (const ClosedForm& c : cases) {
    const Formula f = Formula::parse(c.text, c.params);
    for (const Point& p : c.points) {
      const Parts got = parts(f.eval(p[0], p[1]));
      const Parts want = c.exact(p[0], p[1]);
      for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(got[i], want[i], 1e-13 * (1 + std::abs(want[i])))
            << c.text << " at (" << p[0] << ", " << p[1] << "), part " << i;
      // the plain path computes the same value, operation for operation
      EXPECT_EQ(f.value(p[0], p[1]), got[0]) << c.text;
    }
  }
}

TEST(Formula, PrecedenceAndAssociativity) {
  EXPECT_EQ(Formula::parse("2^3^2").value(0, 0), 512.0);
  EXPECT_EQ(Formula::parse("2**3**2").value(0, 0), 512.0);
  EXPECT_EQ(Formula::parse("-2^2").value(0, 0), -4.0);
  EXPECT_EQ(Formula::parse("(-2)^2").value(0, 0), 4.0);
  EXPECT_EQ(Formula::parse("2^-1").value(0, 0), 0.5);
  EXPECT_EQ(Formula::parse("8 - 2 - 1").value(0, 0), 5.0);
  EXPECT_EQ(Formula::parse("8 / 2 / 2").value(0, 0), 2.0);
  EXPECT_EQ(Formula::parse("1 + 2 * 3").value(0, 0), 7.0);
  EXPECT_EQ(Formula::parse("x - -y").value(1, 2), 3.0);
  EXPECT_EQ(Formula::parse("+x * -y").value(3, 2), -6.0);
  EXPECT_EQ(Formula::parse(".5 + 1e-3 + 2.5E2").value(0, 0), 0.5 + 1e-3 + 250.0);
  EXPECT_EQ(Formula::parse(" x\t*\n2 ").value(4, 0), 8.0);
  EXPECT_EQ(Formula::parse("-x^2").eval(3.0, 0.0).f, -9.0);
}

TEST(Formula, ConstantsFoldIntoImmediates) {
  const Formula folded = Formula::parse("pi*2 + x");
  const Formula unfolded = Formula::parse("y*2 + x");
  EXPECT_EQ(folded.size(), 2u);  // push x, add 2 pi
  EXPECT_EQ(unfolded.size(), 4u);
  EXPECT_LT(folded.size(), unfolded.size());
  EXPECT_EQ(folded.value(1.0, 0.0), kPi * 2 + 1.0);
  EXPECT_EQ(Formula::parse("sin(pi/2) * e^0 * (3 - 1)").size(), 1u);
  EXPECT_EQ(Formula::parse("sin(pi/2) * e^0 * (3 - 1)").value(5, 5), 2.0);
  EXPECT_EQ(Formula::parse("a*x^2", {{"a", 2.0}}).size(), 3u);  // push x, pow 2, mul a
  EXPECT_EQ(Formula::parse("hypot(3, 4)").value(0, 0), 5.0);
  EXPECT_EQ(Formula::parse("atan2(1, x)").size(), 3u);  // the constant pushed below x
  const Formula flat;
  EXPECT_EQ(flat.value(1, 2), 0.0);
  EXPECT_EQ(flat.text(), "0");
}

TEST(Formula, OutsideTheDomainIsNonFiniteNotAnError) {
  EXPECT_TRUE(std::isnan(Formula::parse("sqrt(x)").value(-1, 0)));
  EXPECT_TRUE(std::isinf(Formula::parse("log(x)").value(0, 0)));
  const Jet2<double> j = Formula::parse("1/x").eval(0.0, 0.0);
  EXPECT_FALSE(std::isfinite(j.f));
  EXPECT_FALSE(std::isfinite(j.fxx));
  EXPECT_FALSE(std::isfinite(Formula::parse("sqrt(x)").eval(0.0, 1.0).fx));
  EXPECT_TRUE(std::isnan(Formula::parse("log(-1) + x").value(1, 1)));
}

// A zero made of the formula's own numbers (x^0 - y^0 is 1 - 1) is a number
// like any other in the value: times a NaN it is NaN, in value() and in the
// lowered tape alike (a fuzz finding: the tape took it for a jet's
// structural zero and gave 0).
TEST(Formula, AZeroOfTheFormulasOwnNumbersTimesNaNIsNaNOnEveryPath) {
  for (const std::string text :
       {"x^0.5*(x^0 - y^0) - 4", "(y^0 - x^0)*log(x) + y", "sqrt(x)*(x^0 - 1)", "5 - y - x^a*(x^0 - y^0) - x^-4"}) {
    const Formula f = Formula::parse(text, {{"a", 0.5}});
    ASSERT_TRUE(f.tape().usable()) << text;
    for (const Point& p : std::vector<Point>{{-1.0, 0.5}, {-1e300, 1e-300}}) {
      EXPECT_TRUE(std::isnan(f.value(p[0], p[1]))) << text;
      EXPECT_TRUE(std::isnan(f.eval(p[0], p[1]).f)) << text;
    }
    // where the factor is finite the zero stays a zero
    EXPECT_EQ(f.value(4.0, 0.5), f.eval(4.0, 0.5).f) << text;
    EXPECT_TRUE(std::isfinite(f.eval(4.0, 0.5).f)) << text;
  }
}

// slopes off the native path (the tape, and the stack interpreter for a
// formula too deep for the tape) gives eval's derivatives bit for bit and no
// value (NaN): its out-of-line fallback writes them through the buffer the
// native code writes.
TEST(Formula, SlopesAreEvalsDerivativesOnTheTapeAndOnTheStackInterpreter) {
  std::string deep = "sin(x)*y";
  for (int i = 0; i < 20; ++i) deep = (i % 2 ? "x*(" : "y+(") + deep + ")";
  for (const std::string& text : {std::string("0.05*sin(2*x)*cos(3*y) + 0.1*x^2"), "0.01*(" + deep + ")"}) {
    const Formula f = Formula::parse(text);
    ASSERT_FALSE(f.is_native()) << text;
    for (const Point& p : std::vector<Point>{{0.3, -0.7}, {-1.9, 2.4}}) {
      const Parts slopes = parts(f.slopes(p[0], p[1])), full = parts(f.eval(p[0], p[1]));
      EXPECT_TRUE(std::isnan(slopes[0])) << text;
      EXPECT_TRUE(std::isfinite(full[0])) << text;
      for (std::size_t i = 1; i < 6; ++i) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(slopes[i]), std::bit_cast<std::uint64_t>(full[i]))
            << text << " part " << i;
        EXPECT_TRUE(std::isfinite(slopes[i])) << text << " part " << i;
      }
    }
  }
  EXPECT_TRUE(Formula::parse("0.05*sin(2*x)*cos(3*y) + 0.1*x^2").tape().usable());
  EXPECT_FALSE(Formula::parse("0.01*(" + deep + ")").tape().usable()) << "the deep formula fits the tape";
}

struct ErrorCase {
  std::string text;
  std::string message;
  int column;
  std::map<std::string, double> params = {};
};

TEST(Formula, ErrorsSayWhatAndWhere) {
  const std::string smooth = " is not smooth: the landscape needs continuous second derivatives (docs/model.md); ";
  // every reserved name has this sentence (test_formula_vocabulary.cpp has them all)
  const std::string shadows =
      " shadows a name of the formula language (x y pi e sin cos tan asin acos atan sinh cosh tanh exp log sqrt "
      "atan2 hypot abs min max sign floor ceil round); rename it";
  const std::vector<ErrorCase> cases = {
      {"", "empty formula", 1},
      {"  \t ", "empty formula", 1},
      {"x + z", "unknown name 'z'; a formula knows x, y, pi, e and no params", 5},
      {"a*x + c", "unknown name 'c'; a formula knows x, y, pi, e and the params a, b", 7, {{"a", 1}, {"b", 2}}},
      {"Sin(x)", "unknown function 'Sin'; names are case-sensitive: did you mean 'sin'?", 1},
      {"2 * foo(x)",
       "unknown function 'foo'; the functions are "
       "sin cos tan asin acos atan sinh cosh tanh exp log sqrt atan2 hypot",
       5},
      {"atan2(x)", "atan2 takes 2 arguments, got 1", 1},
      {"1 + sin(x, y)", "sin takes 1 argument, got 2", 5},
      {"hypot()", "hypot takes 2 arguments, got 0", 1},
      {"(x + 1", "missing ')' to close this '('", 1},
      {"x * sin(x", "missing ')' to close this '('", 8},
      {"x + 1)", "')' has no matching '('", 6},
      {"x +", "expected an operand after '+'", 4},
      {"x * / y", "expected an operand after '*'", 5},
      {"(x - )", "expected an operand after '-'", 6},
      {"*x", "expected an operand, found '*'", 1},
      {"()", "expected an operand after '('", 2},
      {"x # y", "unexpected character '#'", 3},
      {"x \xE2\x88\x92 y", "unexpected non-ASCII character (byte 0xE2); formulas are plain ASCII", 3},
      {"1.2.3", "malformed number '1.2.3'", 1},
      {"x + 1e", "malformed number '1e'", 5},
      {"x + 1e+", "malformed number '1e+'", 5},
      {"2x", "malformed number '2x'", 1},
      {"1e999", "number '1e999' is out of range for a double", 1},
      {"abs(x)", "abs" + smooth + "use sqrt(x^2 + eps) for a smooth stand-in", 1},
      {"x + max(x, y)", "max" + smooth + "use (a + b + sqrt((a - b)^2 + eps))/2 for a smooth stand-in", 5},
      {"floor(x)", "floor" + smooth + "use x - sin(2*pi*x)/(2*pi) for a smooth staircase", 1},
      {"sign", "sign" + smooth + "use tanh(x/eps) for a smooth stand-in", 1},
      {"sin x", "sin is a function: write sin(...)", 1},
      {"x(y)", "'x' is not a function; write x*(...) for a product", 1},
      {"x y", "expected an operator before 'y'", 3},
      {"(x, y)", "',' outside a function's argument list", 3},
      {"sin(x y)", "expected an operator, ',' or ')' before 'y'", 7},
      {"(x y)", "expected an operator or ')' before 'y'", 4},
      {"x", "param 'x'" + shadows, 0, {{"x", 1}}},
      {"x", "param 'sqrt'" + shadows, 0, {{"sqrt", 1}}},
      {"x",
       "param name 'a b' is not a name: use letters, digits and '_', starting with a letter or '_'",
       0,
       {{"a b", 1}}},
      {"x", "param 'a' is not finite", 0, {{"a", std::numeric_limits<double>::quiet_NaN()}}},
  };
  for (const ErrorCase& c : cases) {
    try {
      Formula::parse(c.text, c.params);
      ADD_FAILURE() << "no error for '" << c.text << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.message(), c.message) << c.text;
      EXPECT_EQ(e.column(), c.column) << c.text;
      EXPECT_EQ(e.key(), "") << c.text;
    }
  }
}

TEST(Formula, ErrorTextCarriesTheColumnAndTheSceneKey) {
  try {
    Landscape::parse("x + * y");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "column 5: expected an operand after '+'");
    EXPECT_STREQ(e.under("landscape").what(), "'landscape' column 5: expected an operand after '+'");
  }
}

// The message and column of the InputError that parse throws, or "" / -1.
std::pair<std::string, int> error_of(const std::string& text) {
  try {
    Formula::parse(text);
  } catch (const InputError& e) {
    return {e.message(), e.column()};
  }
  return {"", -1};
}

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

TEST(Formula, HostileInputIsAnErrorNotACrash) {
  const std::string depth = "formula nests deeper than 200 levels";
  EXPECT_EQ(error_of(std::string(100000, '(')),
            std::make_pair(std::string("formula is 100000 characters long; the limit is 65536"), 65537));
  EXPECT_EQ(error_of(repeat("x+", 1 << 19)),
            std::make_pair(std::string("formula is 1048576 characters long; the limit is 65536"), 65537));
  EXPECT_EQ(error_of(std::string(60000, '(')), std::make_pair(depth, 201));
  EXPECT_EQ(error_of(std::string(1000, '(') + "x" + std::string(1000, ')')), std::make_pair(depth, 201));
  EXPECT_EQ(error_of(std::string(300, '-') + "x"), std::make_pair(depth, 201));
  EXPECT_EQ(error_of(repeat("2^", 300) + "2"), std::make_pair(depth, 402));
  EXPECT_EQ(error_of(repeat("sin(", 250) + "x" + std::string(250, ')')), std::make_pair(depth, 804));
  EXPECT_EQ(error_of(repeat("x+", 30000)), std::make_pair(std::string("expected an operand after '+'"), 60001));
}

TEST(Formula, DeepButLegalFormulasEvaluate) {
  // 200 levels are allowed
  EXPECT_EQ(Formula::parse(std::string(200, '(') + "x" + std::string(200, ')')).value(0.25, 0), 0.25);
  const Formula sines = Formula::parse(repeat("sin(", 199) + "x" + std::string(199, ')'));
  double s = 0.7;
  for (int i = 0; i < 199; ++i) s = std::sin(s);
  EXPECT_EQ(sines.value(0.7, 0), s);
  // a long flat sum needs a stack of two
  const Formula sum = Formula::parse(repeat("x+", 32767) + "y");
  EXPECT_EQ(sum.stack_depth(), 2u);
  EXPECT_EQ(sum.value(1.0, 2.0), 32769.0);
  EXPECT_EQ(sum.eval(1.0, 2.0).fx, 32767.0);
  // the deepest stack a formula can ask for: three pending operands per level
  const Formula deep = Formula::parse(repeat("y+y*atan2(x,", 200) + "x" + std::string(200, ')'));
  EXPECT_GE(deep.stack_depth(), 3u * 200u);
  EXPECT_LE(deep.stack_depth(), Formula::kMaxStack);
  double g = 0.3;
  for (int i = 0; i < 200; ++i) g = 0.5 + 0.5 * std::atan2(0.3, g);
  EXPECT_EQ(deep.value(0.3, 0.5), g);
  EXPECT_EQ(deep.eval(0.3, 0.5).f, g);
}

TEST(Formula, TokenSoupParsesOrFailsWithAColumnInsideTheText) {
  const std::vector<std::string> pieces = {"x",      "y",      "2",    ".5",  "1e-3", "pi", "e",  "a", "+",
                                           "-",      "*",      "/",    "^",   "**",   "(",  ")",  ",", "sin(",
                                           "atan2(", "hypot(", "abs(", "foo", " ",    "#",  "1e", "q("};
  std::uint64_t state = 12345;
  int parsed = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::string text;
    const int n = 1 + trial % 12;
    for (int i = 0; i < n; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      text += pieces[(state >> 33) % pieces.size()];
    }
    try {
      const Formula f = Formula::parse(text, {{"a", 0.5}});
      const Jet2<double> j = f.eval(0.3, 0.4);
      EXPECT_TRUE(std::isnan(j.f) || j.f == f.value(0.3, 0.4)) << text;
      ++parsed;
    } catch (const InputError& e) {
      EXPECT_GE(e.column(), 1) << text;
      EXPECT_LE(e.column(), static_cast<int>(text.size()) + 1) << text;
      EXPECT_FALSE(e.message().empty()) << text;
    }
  }
  EXPECT_GT(parsed, 100);
}

// An AD number over the two directions (x, y): the derivative of each Jet2
// part along them is the next order, so fx' must equal (fxx, fxy) etc.
using AD2 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2, 1>>;

TEST(Formula, AutoDiffScalarGivesThirdOrderConsistentJets) {
  const std::vector<std::string> texts = {"exp(-(x^2+y^2))",
                                          "atan2(y, x) + hypot(x, y)",
                                          "x^y + 2^-x",
                                          "atan(x*y) + 3/(x + y) + y/(x*x + 1)",
                                          "tan(x) - sqrt(x*y)",
                                          "asin(x/2)*acos(y/2)",
                                          "cos(x*pi + pi)/10 - y/10",
                                          "log(x)*tanh(y) + x^1.5",
                                          "sinh(x)*cosh(y) - x^-3"};
  const double x0 = 0.6, y0 = 0.9;
  for (const std::string& text : texts) {
    const Formula f = Formula::parse(text);
    const Jet2<double> d = f.eval(x0, y0);
    const Jet2<AD2> a = f.eval(AD2(x0, 2, 0), AD2(y0, 2, 1));
    const double tol = 1e-13;
    EXPECT_NEAR(a.f.value(), d.f, tol) << text;
    EXPECT_NEAR(a.f.derivatives()[0], d.fx, tol * (1 + std::abs(d.fx))) << text;
    EXPECT_NEAR(a.f.derivatives()[1], d.fy, tol * (1 + std::abs(d.fy))) << text;
    EXPECT_NEAR(a.fx.derivatives()[0], d.fxx, tol * (1 + std::abs(d.fxx))) << text;
    EXPECT_NEAR(a.fx.derivatives()[1], d.fxy, tol * (1 + std::abs(d.fxy))) << text;
    EXPECT_NEAR(a.fy.derivatives()[0], d.fxy, tol * (1 + std::abs(d.fxy))) << text;
    EXPECT_NEAR(a.fy.derivatives()[1], d.fyy, tol * (1 + std::abs(d.fyy))) << text;
  }
  // third derivatives of exp(-(x^2 + y^2)) in closed form
  const Jet2<AD2> a = Formula::parse("exp(-(x^2+y^2))").eval(AD2(x0, 2, 0), AD2(y0, 2, 1));
  const double g = std::exp(-(x0 * x0 + y0 * y0));
  EXPECT_NEAR(a.fxx.derivatives()[0], (12 * x0 - 8 * x0 * x0 * x0) * g, 1e-14);
  EXPECT_NEAR(a.fxx.derivatives()[1], (4 * x0 * x0 - 2) * (-2 * y0) * g, 1e-14);
}

TEST(Formula, EvaluatesOnTheIntegratorsAutoDiffType) {
  using AD14 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 14, 1>>;
  const Landscape land = Landscape::parse("a*hypot(x, y)^2 + atan(y)", {{"a", 0.5}});
  const Jet2<AD14> j = land.at(AD14(0.3, 14, 12), AD14(-0.2, 14, 13));
  EXPECT_NEAR(j.f.value(), land.height(0.3, -0.2), 1e-15);
  EXPECT_NEAR(j.fx.derivatives()[12], 1.0, 1e-14);  // fxx of x^2/2
  EXPECT_NEAR(j.fy.derivatives()[12], 0.0, 1e-14);
  EXPECT_EQ(j.fx.derivatives()[0], 0.0);
}

TEST(Formula, LandscapeIsAThinWrapper) {
  const Landscape land = Landscape::parse("cos(x*pi + pi)/10 - y/10");
  EXPECT_EQ(land.text(), "cos(x*pi + pi)/10 - y/10");
  EXPECT_EQ(land.height(0.5, 1.0), land.at(0.5, 1.0).f);
  EXPECT_NEAR(land.height(0.0, 1.0), -0.2, 1e-16);
  EXPECT_EQ(Landscape().height(3, 4), 0.0);
}

}  // namespace
}  // namespace rb

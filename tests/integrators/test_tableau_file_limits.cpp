// Tableau files at the edges of what the suite takes: order_tolerance at
// most 1e-10, fractions checked exactly, more than 16 stages (Feagin's
// 10(8) has 17), the stage limit named on A, residual digits in messages
// and the embedded order in `rollbench list`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "integrators/controllers/controller.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "integrators/tableau_file.hpp"
#include "problems/input_error.hpp"
#include "tests/integrators/fixtures.hpp"
#include "tests/integrators/tableau_error.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb {
namespace {

// Ruuth's SSP(5,3) (Math. Comp. 75, 2006), as nodepy gives it in Shu-Osher
// form, turned into Butcher form and rounded to 10 significant digits: its
// order conditions hold to ~9e-11 and its rows sum to c to ~1.0000001e-10.
const std::string kSsp53Printed = R"("c": [0.0, 0.3772689153, 0.7545378307, 0.7289856616, 0.6992261359],
  "A": [[0.0, 0.0, 0.0, 0.0, 0.0], [0.3772689153, 0.0, 0.0, 0.0, 0.0], [0.3772689153, 0.3772689153, 0.0, 0.0, 0.0],
        [0.2429952205, 0.2429952205, 0.2429952205, 0.0, 0.0],
        [0.1535890677, 0.1535890677, 0.1535890677, 0.2384589328, 0.0]],
  "b": [0.2067340209, 0.2067340209, 0.1170972518, 0.1818025601, 0.2876321463])";

std::string ssp53(const std::string& extra) { return "{\"name\": \"ssp53\", " + extra + kSsp53Printed + "}"; }

// Classical RK4 with b_1 and b_4 given by the caller, other entries exact.
std::string rk4_with(const std::string& extra, const std::string& b1, const std::string& b4) {
  return R"({"name": "rk4x", )" + extra + R"("c": [0, 0.5, 0.5, 1],
  "A": [[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1, 0]],
  "b": [)" +
         b1 + R"(, 0.3333333333333333, 0.3333333333333333, )" + b4 + "]}";
}

std::string error_of(const std::string& text) { return testing::tableau_error_of(text); }

const std::string f = "tableau file 't.json': ";

TEST(TableauFileLimits, AToleranceLooserThanTenToTheMinusTenIsRefused) {
  const std::string rule = "must be a number > 0 and at most 1e-10 (the order conditions are checked to it), not ";
  EXPECT_EQ(error_of(ssp53(R"("order_tolerance": 1e-9, )")), f + "'order_tolerance': " + rule + "1e-09");
  EXPECT_EQ(error_of(ssp53(R"("order_tolerance": 1e-6, )")), f + "'order_tolerance': " + rule + "1e-06");
  EXPECT_EQ(error_of(ssp53(R"("order_tolerance": 0, )")), f + "'order_tolerance': " + rule + "0");
  EXPECT_EQ(error_of(ssp53(R"("order_tolerance": "1e-9", )")),
            f + "'order_tolerance': order_tolerance is a string, not a number");
}

TEST(TableauFileLimits, ATenDigitTableMissesEvenTheLoosestTolerance) {
  // its rows miss c by 1.0000001e-10: printed digits are not a tableau
  EXPECT_EQ(error_of(ssp53("")), f + "'c': c[2] must equal the sum of row 2 of A");
  EXPECT_EQ(error_of(ssp53(R"("order_tolerance": 1e-10, )")), f + "'c': c[2] must equal the sum of row 2 of A");
}

TEST(TableauFileLimits, ATableWithinItsToleranceLoadsAndOneBeyondIsRefused) {
  // b_1 and b_4 moved by 3e-11 each way: the order-2 condition misses by 3e-11
  const std::string near = rk4_with(R"("order": 4, )", "0.16666666669666666", "0.16666666663666665");
  EXPECT_EQ(error_of(near).rfind(f + "'order': tableau 'rk4x' declares order 4 but satisfies the order conditions "
                                     "only to order 1 (tree [τ] of order 2: ",
                                 0),
            0u)
      << error_of(near);
  const TableauFile loose = parse_tableau_file(
      rk4_with(R"("order": 4, "order_tolerance": 1e-10, )", "0.16666666669666666", "0.16666666663666665"), "t.json");
  EXPECT_EQ(loose.tableau.order(), 4);
}

TEST(TableauFileLimits, ABrokenRk4IsRefusedNamingTheConditionItBreaks) {
  // truly order 1 (b_1 + 1.8e-6, b_4 - 1.8e-6) and not convergent (sum b = 1 + 9e-7):
  // each met its conditions to 1e-6, the old loosest tolerance
  EXPECT_EQ(error_of(rk4_with(R"("order": 4, "order_tolerance": 1e-10, )", "0.1666684666666667", "0.1666648666666667"))
                .rfind(f + "'order': tableau 'rk4x' declares order 4 but satisfies the order conditions only to "
                           "order 1 (tree [τ] of order 2: ",
                       0),
            0u);
  const std::string diverging =
      error_of(rk4_with(R"("order": 4, "order_tolerance": 1e-10, )", "0.1666675666666667", "0.1666666666666667"));
  EXPECT_EQ(diverging.rfind(f + "'order': tableau 'rk4x' declares order 4 but satisfies the order conditions only "
                                "to order 0 (tree τ of order 1: Phi = 1.0000009",
                            0),
            0u)
      << diverging;
}

TEST(TableauFileLimits, FractionsAreCheckedExactly) {
  const std::string exact_rk4 = R"({"name": "rk4q", "c": [0, "1/2", "1/2", 1],
  "A": [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, 0.5, 0, 0], [0, 0, "1", 0]],
  "b": ["1/6", "1/3", "1/3", "1/6"]})";
  const TableauFile q = parse_tableau_file(exact_rk4, "t.json");
  EXPECT_EQ(q.tableau.order(), 4);  // found exactly: order 5's conditions fail
  EXPECT_EQ(q.tableau.coefficients().b[0], 1.0 / 6.0);
  // 1/6 + 1/6e15: within any tolerance in doubles, but not order 1 exactly
  const std::string off = R"({"name": "rk4q", "order": 4, "c": [0, "1/2", "1/2", 1],
  "A": [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]],
  "b": ["1/6", "1/3", "1/3", "1000000000000001/6000000000000000"]})";
  const std::string e = error_of(off);
  EXPECT_EQ(e.rfind(f + "'b': the weights declare order 4 but satisfy the order conditions exactly only to order 0 "
                        "(tree τ of order 1: ",
                    0),
            0u)
      << e;
  // rows that miss c exactly
  std::string row = exact_rk4;
  row.replace(row.find(R"(["1/2", 0, 0, 0])"), 16, R"(["1/3", 0, 0, 0])");
  EXPECT_EQ(error_of(row), f + "'c': c[1] must equal the sum of row 1 of A exactly (the file gives every "
                               "coefficient exactly)");
  // one inexact decimal: the whole file is checked to its tolerance in doubles
  std::string decimal = off;
  decimal.replace(decimal.find(R"("1/3", "1/3")"), 12, R"(0.3333333333333333, "1/3")");
  EXPECT_EQ(parse_tableau_file(decimal, "t.json").tableau.order(), 4);
}

TEST(TableauFileLimits, AFractionMustBeIntegersUpToTwoToThe53) {
  const auto with_b1 = [](const std::string& b1) {
    return R"({"name": "rk4q", "c": [0, 0.5, 0.5, 1], "A": [[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0],
      [0, 0, 1, 0]], "b": [)" +
           b1 + R"(, "1/3", "1/3", "1/6"]})";
  };
  const std::string rule = ", not a number or a fraction \"p/q\" (integers up to 2^53, q > 0)";
  EXPECT_EQ(error_of(with_b1(R"("1/0")")), f + "'b': entry 0 is the string \"1/0\"" + rule);
  EXPECT_EQ(error_of(with_b1(R"("one/six")")), f + "'b': entry 0 is the string \"one/six\"" + rule);
  EXPECT_EQ(error_of(with_b1(R"("1/6/1")")), f + "'b': entry 0 is the string \"1/6/1\"" + rule);
  EXPECT_EQ(error_of(with_b1(R"("1/ 6")")), f + "'b': entry 0 is the string \"1/ 6\"" + rule);
  EXPECT_EQ(error_of(with_b1(R"("1/9007199254740993")")),
            f + "'b': entry 0 is the string \"1/9007199254740993\"" + rule);
  EXPECT_EQ(parse_tableau_file(with_b1(R"("+1/6")"), "t.json").tableau.order(), 4);
}

TEST(TableauFileLimits, ResidualsShowInTheDigitsPrinted) {
  // order 4 declared for a third-order table: Phi and 1/gamma differ in their printed digits
  const std::string e = error_of(rk4_with(R"("order": 4, )", "0.1676666666666667", "0.1656666666666667"));
  const std::string head = f +
                           "'order': tableau 'rk4x' declares order 4 but satisfies the order conditions only to "
                           "order 1 (tree ";
  ASSERT_EQ(e.rfind(head, 0), 0u) << e;
  double phi = 0, inv_gamma = 0, residual = 0;
  const auto at = e.find(": Phi = ");
  ASSERT_NE(at, std::string::npos) << e;
  ASSERT_EQ(std::sscanf(e.c_str() + at, ": Phi = %lf, 1/gamma = %lf, residual %lf", &phi, &inv_gamma, &residual), 3)
      << e;
  // the printed numbers reproduce the printed residual to its three digits
  EXPECT_NEAR(phi - inv_gamma, residual, 1e-3 * std::abs(residual)) << e;
}

// n explicit Euler substeps of h/n as one n-stage tableau of order 1
std::string euler_substeps(int n) {
  std::ostringstream t;
  t.precision(17);
  t << R"({"name": "euler)" << n << R"(", "order": 1, "c": [)";
  for (int i = 0; i < n; ++i) t << (i ? ", " : "") << static_cast<double>(i) / n;
  t << R"(], "A": [)";
  for (int i = 0; i < n; ++i) {
    t << (i ? ", " : "") << "[";
    for (int j = 0; j < n; ++j) t << (j ? ", " : "") << (j < i ? 1.0 / n : 0.0);
    t << "]";
  }
  t << R"(], "b": [)";
  for (int j = 0; j < n; ++j) t << (j ? ", " : "") << 1.0 / n;
  t << "]}";
  return t.str();
}

TEST(TableauFileLimits, SeventeenStagesRunAsSeventeenEulerSubsteps) {
  // Feagin 10(8)'s stage count: a tableau past the old limit of 16 steps as it says
  const TableauFile file = parse_tableau_file(euler_substeps(17), "t.json");
  ASSERT_EQ(file.tableau.stages(), 17);
  const auto rk17 = rk_method(file.tableau, "rk-euler17", kConstantController);
  const Problem& valley = testing::valley();
  const RunResult big = rk17->integrate(valley, testing::fixed(0.017, 0.17));
  const RunResult small = find_integrator("euler").integrate(valley, testing::fixed(0.001, 0.17));
  ASSERT_EQ(big.status, Status::ok) << big.message;
  ASSERT_EQ(small.status, Status::ok) << small.message;
  EXPECT_EQ(big.cost.rhs_evals, small.cost.rhs_evals);  // 10 steps x 17 stages, 170 Euler steps
  EXPECT_LT((big.final_state - small.final_state).cwiseAbs().maxCoeff(), 1e-13);
  // and it is not merely close: the 17th stage matters (16 substeps of h/17 end elsewhere)
  const RunResult short_run = find_integrator("euler").integrate(valley, testing::fixed(0.001, 0.16));
  EXPECT_GT((big.final_state - short_run.final_state).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(TableauFileLimits, TheStageLimitIsNamedOnA) {
  EXPECT_EQ(parse_tableau_file(euler_substeps(kMaxStages), "t.json").tableau.stages(), kMaxStages);
  EXPECT_EQ(error_of(euler_substeps(kMaxStages + 1)), f + "'A': a tableau needs 1 to " + std::to_string(kMaxStages) +
                                                          " stages, got " + std::to_string(kMaxStages + 1));
}

TEST(TableauFileLimits, ListShowsTheEmbeddedOrder) {
  const std::filesystem::path file = robustness::temp_path("tableau-bs-list.json");
  std::ofstream(file) << R"({"name": "bs-list", "order": 3, "err_order": 2,
  "butcher": [[0, 0, 0, 0, 0], [0.5, 0.5, 0, 0, 0], [0.75, 0, 0.75, 0, 0],
              [1, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0],
              [0, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0]],
  "b_err": [0.2916666666666667, 0.25, 0.3333333333333333, 0.125]})";
  const robustness::CliOutcome list = robustness::rollbench("list --tableau " + file.string());
  ASSERT_EQ(list.code, 0) << list.err;
  const auto line_of = [&](const std::string& name) {
    const auto at = list.out.find("  " + name + " ");
    if (at == std::string::npos) return std::string("missing");
    return list.out.substr(at, list.out.find('\n', at) - at);
  };
  EXPECT_NE(line_of("rk-bs-list-adaptive").find(" 3(2)  adaptive "), std::string::npos)
      << line_of("rk-bs-list-adaptive");
  EXPECT_NE(line_of("rkmk-bs-list-adaptive").find(" 3(2)  adaptive "), std::string::npos);
  EXPECT_NE(line_of("rk-bs-list").find("    3  fixed "), std::string::npos) << line_of("rk-bs-list");
  // the shipped pairs too
  EXPECT_NE(line_of("rkmk-dp54-adaptive").find(" 5(4)  adaptive "), std::string::npos) << line_of("rkmk-dp54-adaptive");
}

}  // namespace
}  // namespace rb

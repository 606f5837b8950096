// Tableau files (docs/formats.md, "Butcher tableau"): both layouts, the orders
// found or checked, the integrators a file gives, and the exact error of
// each kind of bad file.
#include <gtest/gtest.h>

#include "integrators/registry.hpp"
#include "integrators/tableau_file.hpp"
#include "integrators/user_tableaux.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"
#include "tests/integrators/tableau_error.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb {
namespace {

const std::string kRalston3 = R"json({
  "name": "ralston3", "order": 3,
  "c": [0, 0.5, 0.75],
  "A": [[0, 0, 0], [0.5, 0, 0], [0, 0.75, 0]],
  "b": [0.2222222222222222, 0.3333333333333333, 0.4444444444444444],
  "b_err": null, "source": "Ralston (1962)"
})json";

// Bogacki-Shampine 3(2) in the seminar's layout, with its embedded weights.
const std::string kBs32 = R"({
  "name": "bs", "order": 3, "err_order": 2,
  "butcher": [[0, 0, 0, 0, 0], [0.5, 0.5, 0, 0, 0], [0.75, 0, 0.75, 0, 0],
              [1, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0],
              [0, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0]],
  "b_err": [0.2916666666666667, 0.25, 0.3333333333333333, 0.125]
})";

// The text with the first occurrence of from replaced by to.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the text");
  return text.replace(at, from.size(), to);
}

std::string error_of(const std::string& text) { return testing::tableau_error_of(text); }

TEST(TableauFile, ReadsFormatsExampleWithItsOrder) {
  const TableauFile f = parse_tableau_file(kRalston3, "t.json");
  EXPECT_EQ(f.tableau.name(), "ralston3");
  EXPECT_EQ(f.tableau.order(), 3);
  EXPECT_TRUE(f.order_declared);
  EXPECT_EQ(f.tableau.stages(), 3);
  EXPECT_EQ(f.tableau.a(2, 1), 0.75);
  EXPECT_EQ(f.tableau.c(1), 0.5);
  EXPECT_FALSE(f.tableau.has_error_estimate());
  EXPECT_EQ(f.tableau.source(), "Ralston (1962)");
}

TEST(TableauFile, WithoutAnOrderTheHighestThatHoldsIsTaken) {
  const TableauFile f = parse_tableau_file(with(kRalston3, R"("order": 3,)", ""), "t.json");
  EXPECT_EQ(f.tableau.order(), 3);
  EXPECT_FALSE(f.order_declared);
}

TEST(TableauFile, ReadsTheSeminarsButcherLayoutAndTheEmbeddedWeights) {
  const TableauFile f = parse_tableau_file(kBs32, "t.json");
  EXPECT_EQ(f.tableau.total_stages(), 4);
  EXPECT_EQ(f.tableau.c(2), 0.75);
  EXPECT_EQ(f.tableau.a(2, 1), 0.75);
  EXPECT_EQ(f.tableau.b(3), 0.0);
  EXPECT_EQ(f.tableau.order(), 3);
  EXPECT_EQ(f.tableau.embedded_order(), 2);
  ASSERT_EQ(f.tableau.e().size(), 4u);
  // one tableau with its embedded weights: FSAL (the last row is b at c =
  // 1), 3 stages at fixed steps and 4 an attempt, error estimate O(h^3)
  const Tableau& p = f.tableau;
  EXPECT_EQ(p.fsal_stage(), 3);
  EXPECT_EQ(p.stages(), 3);
  EXPECT_EQ(p.attempt_stages(), 4);
  EXPECT_EQ(p.error_order(), 3);
  EXPECT_EQ(p.embedded_order(), 2);
  EXPECT_NEAR(p.e()[3], -0.125, 1e-16);
  // without err_order it is the highest order b_err holds
  EXPECT_EQ(parse_tableau_file(with(kBs32, R"("err_order": 2,)", ""), "t.json").tableau.embedded_order(), 2);
}

TEST(TableauFile, AFileGivesRkAndRkmkAndWithBerrTheirAdaptiveVariants) {
  const std::vector<std::unique_ptr<Integrator>> plain = integrators_of(parse_tableau_file(kRalston3, "t.json"));
  ASSERT_EQ(plain.size(), 2u);
  EXPECT_EQ(plain[0]->name(), "rk-ralston3");
  EXPECT_EQ(plain[0]->family(), "rk");
  EXPECT_EQ(plain[1]->name(), "rkmk-ralston3");
  EXPECT_EQ(plain[1]->family(), "rkmk");
  EXPECT_EQ(plain[1]->declared_order(), 3);
  const std::vector<std::unique_ptr<Integrator>> pair = integrators_of(parse_tableau_file(kBs32, "t.json"));
  ASSERT_EQ(pair.size(), 4u);
  // at fixed steps the FSAL stage is left out: 3 stages, 3 rhs a step
  for (std::size_t i : {0u, 1u}) {
    const RunResult run = pair[i]->integrate(testing::valley(), testing::every(0.1, 1.0, 0.01));
    ASSERT_EQ(run.status, Status::ok) << pair[i]->name();
    EXPECT_EQ(run.cost.rhs_evals, 3 * run.cost.steps) << pair[i]->name();
  }
  EXPECT_EQ(pair[2]->name(), "rk-bs-adaptive");
  EXPECT_TRUE(pair[2]->adaptive());
  EXPECT_EQ(pair[3]->name(), "rkmk-bs-adaptive");
  EXPECT_TRUE(pair[3]->adaptive());
  EXPECT_EQ(pair[3]->declared_order(), 3);
}

TEST(TableauFile, TheFilesPairRunsAsTheBuiltInPairDoes) {
  // rkmk-<name>-adaptive on Bogacki-Shampine typed as a file takes the steps
  // of the built-in rkmk-bs32-adaptive (outputs at t_end only: no dense output needed)
  const Problem problem = make_problem(load_scene("bowl-planar"));
  RunOptions options;
  options.t_end = 2.0;
  options.tolerances = Tolerances(1e-8, 1e-8);
  const RunResult mine = integrators_of(parse_tableau_file(kBs32, "t.json"))[3]->integrate(problem, options);
  const RunResult built_in = find_integrator("rkmk-bs32-adaptive").integrate(problem, options);
  ASSERT_EQ(mine.status, Status::ok) << mine.message;
  EXPECT_GT(mine.cost.steps, 100);
  EXPECT_EQ(mine.cost.steps, built_in.cost.steps);
  EXPECT_EQ(mine.cost.rejected, built_in.cost.rejected);
  EXPECT_EQ(mine.cost.rhs_evals, built_in.cost.rhs_evals);
  EXPECT_LT((mine.final_state - built_in.final_state).norm(), 1e-13);
  // the flat variant: FSAL, so 3 new stages an accepted step (+1 at the start, +2 for the first step's guess)
  const RunResult flat = integrators_of(parse_tableau_file(kBs32, "t.json"))[2]->integrate(problem, options);
  ASSERT_EQ(flat.status, Status::ok) << flat.message;
  EXPECT_EQ(flat.cost.rhs_evals, 3 * (flat.cost.steps + flat.cost.rejected) + 3);
}

TEST(TableauFile, TheFilesMethodsEndEachStopSceneWithItsStatus) {
  // as tests/robustness/test_failures.cpp drives every family: a non-finite
  // trial step is shrunk, not the end, until the state itself stops
  const std::vector<std::unique_ptr<Integrator>> methods = integrators_of(parse_tableau_file(kBs32, "t.json"));
  const std::pair<const char*, Status> cases[] = {{"stop-nonfinite.json", Status::diverged},
                                                  {"stop-lift-off.json", Status::lift_off},
                                                  {"stop-curvature.json", Status::curvature},
                                                  {"stop-domain.json", Status::domain}};
  for (const auto& method : methods)
    for (const auto& [file, status] : cases) {
      SCOPED_TRACE(method->name() + " on " + file);
      const Problem p = robustness::data_problem(file);
      const RunResult r = method->integrate(p, robustness::options_for(*method, p.t_end(), 1e-3, 1e-8, 0.01));
      EXPECT_EQ(status_name(r.status), status_name(status)) << r.message;
      EXPECT_GT(r.stop_time, 0.0);
      EXPECT_LT(r.stop_time, p.t_end());
      EXPECT_TRUE(r.final_state.allFinite());
    }
}

TEST(TableauFile, TheShippedExamplesLoad) {
  const std::string dir = std::string(RB_SOURCE_DIR) + "/examples/tableaux/";
  EXPECT_EQ(load_tableau_file(dir + "ralston3.json").tableau.order(), 3);
  const TableauFile rk4 = load_tableau_file(dir + "seminar-rk4.json");
  EXPECT_EQ(rk4.tableau.order(), 4);
  EXPECT_EQ(rk4.tableau.satisfied_order(), 4);
  const TableauFile bs = load_tableau_file(dir + "bogacki-shampine.json");
  EXPECT_EQ(bs.tableau.order(), 3);
  EXPECT_EQ(bs.tableau.embedded_order(), 2);
  // A printed to 10 digits, b polished: order 3 holds to the default tolerance, order 4 fails
  const TableauFile ssp = load_tableau_file(dir + "ssp53-ruuth.json");
  EXPECT_EQ(ssp.tableau.order(), 3);
  EXPECT_EQ(ssp.tableau.satisfied_order(), 3);
  EXPECT_EQ(ssp.tableau.coefficients().order_tolerance, kOrderConditionTolerance);
}

TEST(TableauFile, TheShippedExamplesConvergeAtTheirDeclaredOrder) {
  // as the registry-wide order test measures every built-in method: the
  // valley with a sideways start, against rkmk4 at h = 5e-5
  RunOptions fine;
  fine.t_end = 1.0;
  fine.h = 5e-5;
  const FlatState ref = find_integrator("rkmk4").integrate(testing::valley(), fine).final_state;
  const std::string dir = std::string(RB_SOURCE_DIR) + "/examples/tableaux/";
  for (const char* file : {"ralston3.json", "seminar-rk4.json", "bogacki-shampine.json", "ssp53-ruuth.json"})
    for (const auto& method : integrators_of(load_tableau_file(dir + file))) {
      if (method->adaptive()) continue;
      SCOPED_TRACE(method->name());
      const testing::Convergence c = testing::measure_convergence(*method, testing::valley(), 1.0, ref);
      ASSERT_GE(c.contact_fit.points, 3);
      EXPECT_NEAR(c.contact_fit.slope, method->declared_order(), 0.2);
      EXPECT_NEAR(c.omega_fit.slope, method->declared_order(), 0.2);
    }
}

TEST(TableauFile, EachKindOfBadFileIsRefusedNamingTheFileAndTheKey) {
  const std::string f = "tableau file 't.json': ";
  // not JSON, or not an object
  EXPECT_EQ(error_of(R"({"name": "x", "order": })"),
            f + "not JSON: parse error at line 1, column 24: syntax error while parsing value - unexpected '}'; "
                "expected '[', '{', or a literal");
  EXPECT_EQ(error_of("[1, 2]"), f + "must be a JSON object, not array");
  // missing and unknown keys, a key twice
  EXPECT_EQ(error_of(with(kRalston3, R"("b": [0.2222222222222222, 0.3333333333333333, 0.4444444444444444],)", "")),
            f + "'b': missing required key (or give butcher instead of c, A and b)");
  EXPECT_EQ(error_of(with(kRalston3, R"("name": "ralston3",)", "")), f + "'name': missing required key");
  EXPECT_EQ(
      error_of(with(kRalston3, R"("order": 3,)", R"("order": 3, "ordre": 3,)")),
      f + "'ordre': unknown key (known: name, order, c, A, b, b_err, err_order, source, butcher, order_tolerance)");
  EXPECT_EQ(error_of(with(kRalston3, R"("order": 3,)", R"("order": 3, "order": 2,)")),
            f + "'order': the key appears more than once");
  // wrong shapes
  EXPECT_EQ(error_of(with(kRalston3, "[0.5, 0, 0]", "[0.5, 0]")),
            f + "'A': row 1 has 2 entries, not 3 (A must be square)");
  EXPECT_EQ(error_of(with(kRalston3, "[0, 0.5, 0.75]", "[0, 0.5]")), f + "'c': has 2 entries, not 3 (A has 3 rows)");
  EXPECT_EQ(
      error_of(with(kRalston3, "[0, 0.75, 0]", R"([0, "3/4s", 0])")),
      f + "'A[2]': entry 1 is the string \"3/4s\", not a number or a fraction \"p/q\" (integers up to 2^53, q > 0)");
  // a fraction is a number: "3/4" is 0.75
  EXPECT_EQ(error_of(with(kRalston3, "[0, 0.75, 0]", R"([0, "3/4", 0])")), "no error");
  EXPECT_EQ(error_of(with(kBs32, "[0, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444, 0]]",
                          "[0, 0.2222222222222222, 0.3333333333333333, 0.4444444444444444]]")),
            f + "'butcher': row 4 has 4 entries, not 5 (butcher must be square)");
  EXPECT_EQ(error_of(with(kRalston3, R"("b_err": null)", R"("butcher": [[0]])")),
            f + "'butcher': give either butcher or c, A and b, not both");
  // implicit, non-finite, rows not summing to c
  EXPECT_EQ(error_of(with(kRalston3, "[[0, 0, 0]", "[[0, 0.5, 0]")),
            f + "'A': A must be strictly lower triangular for an explicit method (a[0][1] != 0)");
  EXPECT_EQ(error_of(with(kRalston3, "[0, 0.75, 0]", "[0, 1e400, 0]")),
            f + "'A': not a finite number: number overflow parsing '1e400'");
  EXPECT_EQ(error_of(with(kRalston3, "[0, 0.5, 0.75]", "[0, 0.5, 0.7]")),
            f + "'c': c[2] must equal the sum of row 2 of A");
  // order conditions: the tree, its order and the residual
  EXPECT_EQ(error_of(with(kRalston3, R"("order": 3)", R"("order": 4)")),
            f + "'order': tableau 'ralston3' declares order 4 but satisfies the order conditions only to order 3 "
                "(tree [τ³] of order 4: Phi = 0.229166666666667, 1/gamma = 0.25, residual -2.083e-02)");
  EXPECT_EQ(error_of(with(kRalston3, "0.4444444444444444]", "0.4444]")),
            f + "'order': tableau 'ralston3' declares order 3 but satisfies the order conditions only to order 0 "
                "(tree τ of order 1: Phi = 0.999955555555556, 1/gamma = 1, residual -4.444e-05)");
  EXPECT_EQ(error_of(with(with(kRalston3, R"("order": 3,)", ""), "0.4444444444444444]", "0.4444]")),
            f + "'b': the weights satisfy no order condition (tree τ of order 1: Phi = 0.999955555555556, 1/gamma = 1, "
                "residual -4.444e-05)");
  EXPECT_EQ(error_of(with(kBs32, R"("err_order": 2)", R"("err_order": 3)")),
            f + "'b_err': the embedded weights declare err_order 3 but satisfy the order conditions only to order 2 "
                "(tree [τ²] of order 3: Phi = 0.375, 1/gamma = 0.333333333333333, residual 4.167e-02)");
  EXPECT_EQ(error_of(with(kBs32, "0.125]", "0.125, 0]")), f + "'b_err': has 5 entries, not 4 (b has 4)");
  EXPECT_EQ(error_of(with(kRalston3, R"("order": 3)", R"("order": 3.5)")),
            f + "'order': must be an integer from 1 to 10, not 3.5");
  EXPECT_EQ(error_of(with(kRalston3, R"("b_err": null)", R"("err_order": 2)")),
            f + "'err_order': goes with b_err, which the file does not give");
  EXPECT_EQ(error_of(with(kRalston3, R"("ralston3")", R"("ral ston")")),
            f + "'name': must be a string of 1 to 40 letters, digits, '-', '_' or '.' (it names rk-<name>), not "
                "\"ral ston\"");
}

TEST(TableauFile, AnUnreadableFileIsNamed) {
  try {
    load_tableau_file("/nonexistent/t.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "'tableau': cannot read the tableau file '/nonexistent/t.json' (No such file or directory)");
  }
}

}  // namespace
}  // namespace rb

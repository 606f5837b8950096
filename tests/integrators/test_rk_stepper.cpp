// The rk family's one stepper (integrators/families/rk/rk_stepper.hpp): a
// pair's step with its error estimate is the same tableau's fixed step bit
// for bit, its error norm is h e_0 k_0 + h e_1 k_1 + ... against its closed
// form, and a tableau file's pair gives its fixed and adaptive flat members
// (and the Lie ones) from the same code.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/rk/rk_stepper.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/verner76.hpp"
#include "integrators/methods/verner98.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "integrators/tableau_file.hpp"
#include "integrators/user_tableaux.hpp"
#include "tests/integrators/fixtures.hpp"
#include "tests/integrators/heun_euler.hpp"

namespace rb {
namespace {

using testing::valley;

using testing::heun_euler;  // 2 stages, e = b - b_hat = (-1/2, 1/2)

// The pairs of the registry and a 2-stage one (its propagating loop
// unrolled, as bs32's 3 stages are; the others go generic).
std::vector<Tableau> pairs() {
  return {heun_euler(),          methods::bogacki_shampine32(), methods::dormand_prince54(),
          methods::fehlberg78(), methods::verner76(),           methods::verner98()};
}

bool same_bits(const FlatState& a, const FlatState& b) {
  for (int i = 0; i < kFlatSize; ++i)
    if (std::signbit(a[i]) != std::signbit(b[i]) || !(a[i] == b[i])) return false;
  return true;
}

TEST(RkStepper, APairsStepWithItsEstimateIsTheFixedStepBitForBit) {
  const Tolerances tol(1e-6, 1e-9);
  for (const Tableau& tableau : pairs()) {
    SCOPED_TRACE(tableau.name());
    // as rk_method makes them: the fixed functor and the pair from the same maker
    with_rk_stepper<false>(valley(), tableau, Tolerances(), [&](auto& fixed) {
      return with_rk_stepper<true>(valley(), tableau, tol, [&](auto& pair) {
        FlatState y = valley().y0(), next, paired;
        Cost fixed_cost, pair_cost;
        const double hs[] = {0.02, 0.01, 0.03, 0.005};
        double t = 0.0;
        for (const double h : hs) {
          fixed(y, next, t, h, fixed_cost);
          const double err = pair.try_step(t, h, pair_cost);
          EXPECT_TRUE(std::isfinite(err));
          EXPECT_GT(err, 0.0);
          pair.accept(t, h, pair_cost);
          pair.state(paired);
          EXPECT_TRUE(same_bits(paired, next)) << "h " << h << ": " << (paired - next).norm();
          y = next;
          t += h;
        }
        EXPECT_EQ(fixed_cost.rhs_evals, 4 * tableau.stages());
        // the first attempt evaluates its first stage, an FSAL pair's later ones reuse it
        const int first = tableau.fsal_in_attempt() ? 0 : 1;
        EXPECT_EQ(pair_cost.rhs_evals, tableau.attempt_stages() + 3 * (tableau.attempt_stages() - 1 + first));
        return 0;
      });
    });
  }
}

TEST(RkStepper, TheErrorNormIsTheRmsOfTheScaledStepSumOfTheErrorWeights) {
  const Tableau tableau = heun_euler();
  const Tolerances tol(1e-5, 1e-8);
  RkStepper<0> pair(valley(), tableau, tol);
  const double h = 0.05;
  Cost cost;
  const double err = pair.try_step(0.0, h, cost);
  pair.accept(0.0, h, cost);
  FlatState y_new;
  pair.state(y_new);
  // closed form: k_0 = F(y), k_1 = F(y + h k_0), y_new = y + h/2 k_0 + h/2 k_1,
  // error h/2 (k_1 - k_0), each component against atol + rtol max(|y|, |y_new|)
  const FlatState& y = valley().y0();
  FlatState k0, k1;
  ModelMargins m;
  valley().flat_rhs(y.data(), k0.data(), m);
  const FlatState stage = y + h * k0;
  valley().flat_rhs(stage.data(), k1.data(), m);
  EXPECT_TRUE(same_bits(y_new, y + (0.5 * h) * k0 + (0.5 * h) * k1));
  double squares = 0.0;
  for (int i = 0; i < kFlatSize; ++i) {
    const double e = 0.5 * h * (k1[i] - k0[i]);
    const double scale = 1e-8 + 1e-5 * std::max(std::abs(y[i]), std::abs(y_new[i]));
    squares += (e / scale) * (e / scale);
  }
  EXPECT_GT(err, 1.0);  // a coarse step of a first-order estimate at a tight tolerance
  EXPECT_NEAR(err, std::sqrt(squares / kFlatSize), 1e-12 * err);
}

TEST(RkStepper, AtFixedStepsThePairsExtraStagesAreNotEvaluated) {
  // dp54's seventh stage (FSAL) only its error weights use
  const Tableau tableau = methods::dormand_prince54();
  ASSERT_EQ(tableau.stages(), 6);
  ASSERT_EQ(tableau.attempt_stages(), 7);
  const RunResult r = rk_method(tableau, "rk-dp54", kConstantController)->integrate(valley(), testing::fixed(0.1, 1.0));
  ASSERT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.cost.steps, 10);
  EXPECT_EQ(r.cost.rhs_evals, 60);
}

const std::string kHeunEulerFile = R"({
  "name": "he", "order": 2, "err_order": 1,
  "butcher": [[0, 0, 0], [1, 1, 0], [0, 0.5, 0.5]],
  "b_err": [1, 0]
})";

TEST(RkStepper, ATableauFilesPairGivesFixedAndAdaptiveFlatMembersThatStepAlike) {
  const std::vector<std::unique_ptr<Integrator>> made = integrators_of(parse_tableau_file(kHeunEulerFile, "t.json"));
  ASSERT_EQ(made.size(), 4u);
  const std::vector<std::string> names = {"rk-he", "rkmk-he", "rk-he-adaptive", "rkmk-he-adaptive"};
  const std::vector<std::string> families = {"rk", "rkmk", "rk-adaptive", "rkmk-adaptive"};
  for (std::size_t i = 0; i < made.size(); ++i) {
    EXPECT_EQ(made[i]->name(), names[i]);
    EXPECT_EQ(made[i]->family(), families[i]);
  }
  // a tolerance every step meets and an output every h: the adaptive
  // member's steps are clamped onto the outputs, each of h, and its states
  // are the fixed member's bit for bit
  const double h = 0.01;
  RunOptions fixed = testing::every(h, 0.5, h);
  RunOptions loose = testing::tolerance_every(1e3, h, 0.5);
  loose.h = h;
  const RunResult a = made[0]->integrate(valley(), fixed);
  const RunResult b = made[2]->integrate(valley(), loose);
  ASSERT_EQ(a.status, Status::ok);
  ASSERT_EQ(b.status, Status::ok);
  EXPECT_EQ(b.cost.steps, a.cost.steps);
  EXPECT_EQ(b.cost.rejected, 0);
  EXPECT_TRUE(same_bits(b.final_state, a.final_state)) << (b.final_state - a.final_state).norm();
}

}  // namespace
}  // namespace rb

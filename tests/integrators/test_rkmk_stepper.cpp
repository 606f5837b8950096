// The one RKMK stepper (integrators/families/rkmk/rkmk_stepper.hpp): its
// stage loop with the error estimate (an embedded pair's attempt) computes
// the new state with the same arithmetic as without (a fixed step), so a
// pair's accepted steps are its tableau's fixed steps bit for bit; and a
// user tableau's Lie members, fixed and adaptive, come from that stepper.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/rkmk/munthe_kaas.hpp"
#include "integrators/families/rkmk/rkmk_stepper.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/methods/verner76.hpp"
#include "integrators/methods/verner98.hpp"
#include "integrators/user_tableaux.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::shipped_scene;

bool same_bits(const FlatState& a, const FlatState& b) { return std::memcmp(a.data(), b.data(), sizeof(a)) == 0; }

// n steps of h by the pair's attempts, each accepted: the state after each
template <bool General>
std::vector<FlatState> pair_steps(const Problem& p, const Tableau& tableau, double h, int n, Cost& cost) {
  const StageTerms terms(tableau);
  RkmkStages stages;
  const std::vector<double> outputs;
  RkmkStepper<0, ClosedFormExpCoordinates, false, General> pair(p, tableau, terms, ClosedFormExpCoordinates{}, stages,
                                                                Tolerances(1e-6, 1e-9), outputs);
  std::vector<FlatState> states;
  for (int i = 0; i < n; ++i) {
    const double err = pair.try_step(i * h, h, cost);
    EXPECT_TRUE(std::isfinite(err)) << tableau.name() << " step " << i;
    EXPECT_GT(err, 0.0) << tableau.name() << " step " << i;  // an estimate was computed
    pair.accept(i * h, h, cost);
    FlatState y;
    pair.state(y);
    states.push_back(y);
  }
  return states;
}

// After each of 16 steps of 1/64 (exact in binary, so that the fixed-step
// driver's h is the same number): the registered fixed-step path (its
// unrolled stage loop where the tableau has at most four stages) and the
// pair's attempt, on a homogeneous ball and on one with inertia (the pair's
// other code path, stage orientations of an anisotropic ball).
TEST(RkmkStepper, APairsAttemptGivesItsTableausFixedStepBitForBit) {
  const double h = 1.0 / 64;
  const int n = 16;
  for (const char* scene : {"valley-sideways", "chaplygin-valley"}) {
    const Problem& p = shipped_scene(scene);
    if (std::string(scene) == "chaplygin-valley") {
      ASSERT_TRUE(p.model().has_inertia());
      ASSERT_TRUE(p.model().anisotropic());
    }
    for (const Tableau& tableau :
         {methods::bogacki_shampine32(), methods::dormand_prince54(), methods::dormand_prince853(),
          methods::fehlberg78(), methods::verner76(), methods::verner98()}) {
      SCOPED_TRACE(std::string(scene) + " " + tableau.name());
      const auto fixed = rkmk_integrator(tableau, "fixed", kConstantController);
      RunOptions o;
      o.h = h;
      for (int k = 1; k <= n; ++k) o.output_times.push_back(k * h);
      o.t_end = n * h;
      const RunResult run = fixed->integrate(p, o);
      ASSERT_EQ(run.status, Status::ok);
      ASSERT_EQ(run.cost.steps, n);
      Cost cost;
      const std::vector<FlatState> tried = p.model().has_inertia() ? pair_steps<true>(p, tableau, h, n, cost)
                                                                   : pair_steps<false>(p, tableau, h, n, cost);
      ASSERT_EQ(run.output.y.size(), tried.size());
      for (std::size_t k = 0; k < tried.size(); ++k) {
        const FlatState &fixed_step = run.output.y[k], &attempt = tried[k];
        EXPECT_TRUE(same_bits(fixed_step, attempt))
            << "step " << k + 1 << ": R differs by " << (rotation_of(fixed_step) - rotation_of(attempt)).norm()
            << ", z by " << (z_of(fixed_step) - z_of(attempt)).norm();
      }
      // the pair's attempts took the estimate's stages, the fixed steps not
      EXPECT_EQ(cost.dexpinv_evals, n * (tableau.attempt_stages() - 1));
      EXPECT_EQ(run.cost.dexpinv_evals, n * (tableau.stages() - 1));
    }
  }
}

// A fixed step of known shape (stage_terms.hpp: each stage from the one
// before, or every term) sums the same terms as one that reads the rows'
// patterns at run time: the same states, bit for bit; a stepper given a
// shape that is not its tableau's refuses to run. The shaped one is the
// registered one (the closed-form dexpinv fixed at compile time), the other
// reads the kind at run time as well.
template <int S, StageShape Shape>
void expect_shaped_steps_are_runtime_steps(const Tableau& tableau) {
  SCOPED_TRACE(tableau.name());
  const Problem& p = shipped_scene("valley-sideways");
  const StageTerms terms(tableau);
  ASSERT_EQ(terms.shape(S), Shape);
  RkmkStages shaped_stages, runtime_stages;
  RkmkStepper<S, ClosedFormExpCoordinates, false, false, Shape> shaped(p, tableau, terms, ClosedFormExpCoordinates{},
                                                                       shaped_stages);
  RkmkStepper<S, ExpCoordinates, false, false> runtime(p, tableau, terms, ExpCoordinates{DexpinvKind::exact},
                                                       runtime_stages);
  const double h = 1.0 / 64;
  FlatState y = p.y0(), y_runtime = p.y0(), next, next_runtime;
  Cost cost, cost_runtime;
  for (int k = 0; k < 8; ++k) {
    shaped(y, next, k * h, h, cost);
    runtime(y_runtime, next_runtime, k * h, h, cost_runtime);
    ASSERT_TRUE(same_bits(next, next_runtime)) << "step " << k + 1;
    EXPECT_NE(next, y);
    y = next;
    y_runtime = next_runtime;
  }
  EXPECT_EQ(cost.rhs_evals, 8 * S);
}

TEST(RkmkStepper, AFixedStepOfKnownShapeIsTheStepOfItsShapeReadAtRunTime) {
  expect_shaped_steps_are_runtime_steps<2, chain_shape(2)>(methods::heun());
  expect_shaped_steps_are_runtime_steps<3, dense_shape(3)>(methods::kutta3());
  expect_shaped_steps_are_runtime_steps<4, chain_shape(4)>(methods::rk4());
  expect_shaped_steps_are_runtime_steps<4, dense_shape(4)>(methods::rk38());
  const Tableau rk38 = methods::rk38();
  const StageTerms terms(rk38);
  RkmkStages stages;
  using ChainStepper = RkmkStepper<4, ExpCoordinates, false, false, chain_shape(4)>;
  EXPECT_THROW(ChainStepper(shipped_scene("valley-sideways"), rk38, terms, ExpCoordinates{DexpinvKind::exact}, stages),
               std::logic_error);
}

// The comparison above tells dexpinv's kinds apart: the truncated series read
// at run time steps to other states than the closed form.
TEST(RkmkStepper, TheTruncatedDexpinvIsNotTheClosedFormFixedAtCompileTime) {
  const Problem& p = shipped_scene("valley-sideways");
  const Tableau rk4 = methods::rk4();
  const StageTerms terms(rk4);
  RkmkStages closed_stages, truncated_stages;
  RkmkStepper<4, ClosedFormExpCoordinates, false, false> closed(p, rk4, terms, ClosedFormExpCoordinates{},
                                                                closed_stages);
  RkmkStepper<4, ExpCoordinates, false, false> truncated(p, rk4, terms, ExpCoordinates{DexpinvKind::truncated},
                                                         truncated_stages);
  FlatState next, next_truncated;
  Cost cost;
  closed(p.y0(), next, 0.0, 1.0 / 64, cost);
  truncated(p.y0(), next_truncated, 0.0, 1.0 / 64, cost);
  EXPECT_FALSE(same_bits(next, next_truncated));
  EXPECT_LT((next - next_truncated).norm(), 1e-6);  // the kinds differ at O(|u|^5) only
}

// A user tableau with an embedded pair gives flat and Lie members, fixed and
// adaptive; the Lie ones run the same stepper: one step of the adaptive
// member (given first step, loose tolerance: accepted) is the fixed member's.
TEST(RkmkStepper, AUserTableausLieMembersShareTheirStepper) {
  const TableauFile file{.path = "user.json", .tableau = methods::dormand_prince54()};
  const std::vector<std::unique_ptr<Integrator>> made = integrators_of(file);
  ASSERT_EQ(made.size(), 4u);
  const Integrator* fixed = nullptr;
  const Integrator* adaptive = nullptr;
  for (const auto& m : made) {
    if (m->name() == "rkmk-" + file.tableau.name()) fixed = m.get();
    if (m->name() == "rkmk-" + file.tableau.name() + "-adaptive") adaptive = m.get();
  }
  ASSERT_NE(fixed, nullptr);
  ASSERT_NE(adaptive, nullptr);
  EXPECT_EQ(fixed->info().family, "rkmk");
  EXPECT_EQ(adaptive->info().family, "rkmk-adaptive");
  const Problem& p = shipped_scene("bowl-3d");
  RunOptions one;
  one.t_end = 0.0625;
  one.h = one.t_end;
  const RunResult a = fixed->integrate(p, one);
  one.tolerances = Tolerances(1.0, 1.0);
  const RunResult b = adaptive->integrate(p, one);
  ASSERT_EQ(a.status, Status::ok);
  ASSERT_EQ(b.status, Status::ok);
  ASSERT_EQ(a.cost.steps, 1);
  ASSERT_EQ(b.cost.steps, 1);
  ASSERT_EQ(b.cost.rejected, 0);
  EXPECT_TRUE(same_bits(a.final_state, b.final_state));
}

}  // namespace
}  // namespace rb

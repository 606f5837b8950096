// Conformance of the Lie-group methods: the same (v, alpha) trajectory as the
// classical method with the same tableau (R never enters G), R on SO(3), and
// the contrast with classical RK whose R drifts.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "integrators/controllers/controller.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::every;
using testing::valley;

// Ralston's third-order method: a tableau the suite does not ship.
Tableau ralston3() {
  return Tableau("ralston3", 3, {0, 0, 0, 0.5, 0, 0, 0, 0.75, 0}, {2.0 / 9, 1.0 / 3, 4.0 / 9}, {0, 0.5, 0.75});
}

// The shipped tableaus a fixed-step RKMK method may name (MethodInfo::tableau).
Tableau shipped_tableau(const std::string& name) {
  for (const Tableau& t : {methods::euler(), methods::heun(), methods::kutta3(), methods::rk4(), methods::rk38(),
                           methods::dormand_prince54(), methods::fehlberg78()})
    if (t.name() == name) return t;
  throw std::invalid_argument("no shipped tableau '" + name + "'");
}

void expect_same_z_and_rotation_exact(const Integrator& lie, const Integrator& classical) {
  const RunOptions o = every(0.1, 2.0, 0.01);
  const RunResult a = lie.integrate(valley(), o);
  const RunResult b = classical.integrate(valley(), o);
  ASSERT_EQ(a.status, Status::ok);
  ASSERT_EQ(b.status, Status::ok);
  ASSERT_EQ(a.output.y.size(), b.output.y.size());
  for (std::size_t i = 0; i < a.output.y.size(); ++i) {
    EXPECT_LT((z_of(a.output.y[i]) - z_of(b.output.y[i])).norm(), 1e-12) << lie.name() << " at t = " << a.output.t[i];
    EXPECT_LT(rotation_defect(rotation_of(a.output.y[i])), 1e-13) << lie.name();
  }
  EXPECT_EQ(a.cost.rhs_evals, b.cost.rhs_evals);
  EXPECT_EQ(a.cost.exp_evals, a.cost.steps);
}

TEST(MuntheKaas, EveryRegisteredLieMethodMatchesItsClassicalTwinInZ) {
  int checked = 0;
  // every fixed-step RKMK method on a tableau (closed-form dexpinv), read
  // from the registry
  for (const auto& integrator : registry()) {
    const MethodInfo& info = integrator->info();
    if (info.family != "rkmk" || info.adaptive || info.tableau.empty()) continue;
    const Tableau tableau = shipped_tableau(info.tableau);
    expect_same_z_and_rotation_exact(*integrator, *rk_method(tableau, tableau.name(), kConstantController));
    ++checked;
  }
  EXPECT_GE(checked, 6);
  // and the variants of dexpinv, which change u only
  for (const char* name : {"rkmk4-series", "rkmk4-seminar"})
    expect_same_z_and_rotation_exact(find_integrator(name), find_integrator("rk4"));
}

TEST(MuntheKaas, UserTableauPassesTheSameChecks) {
  const std::unique_ptr<Integrator> lie_method = rkmk_method(ralston3(), "rkmk-ralston3", kConstantController);
  const std::unique_ptr<Integrator> classical_method = rk_method(ralston3(), "ralston3", kConstantController);
  const Integrator& lie = *lie_method;
  const Integrator& classical = *classical_method;
  expect_same_z_and_rotation_exact(lie, classical);
  RunOptions fine;
  fine.t_end = 1.0;
  fine.h = 5e-5;
  const FlatState ref = find_integrator("rkmk4").integrate(valley(), fine).final_state;
  for (const Integrator* m : {static_cast<const Integrator*>(&lie), static_cast<const Integrator*>(&classical)}) {
    const testing::Convergence c = testing::measure_convergence(*m, valley(), 1.0, ref);
    EXPECT_NEAR(c.contact_fit.slope, 3.0, 0.2) << m->name();
    EXPECT_NEAR(c.rotation_fit.slope, 3.0, 0.2) << m->name();
  }
}

TEST(MuntheKaas, ExpEulerIsLieEuler) {
  // one step by hand: R1 = exp(h hat(omega(z0))) R0, z1 = z0 + h G(z0)
  const Problem& p = valley();
  const double h = 0.01;
  Vec3 omega;
  ZState G;
  const ZState z0 = z_of(p.y0());
  p.lie_rhs(rotation_of(p.y0()), z0.data(), omega.data(), G.data());
  RunOptions o;
  o.t_end = h;
  o.h = h;
  const RunResult run = find_integrator("exp-euler").integrate(p, o);
  EXPECT_LT((rotation_of(run.final_state) - so3_exp(h * omega) * rotation_of(p.y0())).norm(), 1e-15);
  EXPECT_LT((z_of(run.final_state) - (z0 + h * G)).norm(), 1e-15);
}

// 10^6 steps on a bounded scene: R stays a rotation to rounding with rkmk4.
TEST(MuntheKaas, Rkmk4KeepsRotationForAMillionSteps) {
  const Problem bowl = make_problem(load_scene("bowl-3d"));
  const RunOptions o = every(10.0, 1000.0, 1e-3);
  const RunResult run = find_integrator("rkmk4").integrate(bowl, o);
  ASSERT_EQ(run.status, Status::ok) << run.message;
  EXPECT_EQ(run.cost.steps, 1'000'000);
  double worst = 0.0;
  for (const FlatState& y : run.output.y) worst = std::max(worst, rotation_defect(rotation_of(y)));
  EXPECT_LT(worst, 1e-12);
}

// Classical RK lets R drift, and the drift grows with time: the contrast the
// benchmark is about, documented by assertions.
TEST(MuntheKaas, ClassicalMethodsDriftOffSO3AndTheDriftGrows) {
  const Problem bowl = make_problem(load_scene("bowl-3d"));
  struct Case {
    const char* name;
    double h;
    double min_final_defect;
  };
  for (const Case c : {Case{"rk4", 0.02, 1e-9}, Case{"euler", 1e-3, 1e-3}}) {
    const RunResult run = find_integrator(c.name).integrate(bowl, every(1.0, 100.0, c.h));
    ASSERT_EQ(run.status, Status::ok) << c.name << ": " << run.message;
    const double at_10 = rotation_defect(rotation_of(run.output.y[9]));
    const double at_100 = rotation_defect(rotation_of(run.output.y.back()));
    EXPECT_GT(at_100, c.min_final_defect) << c.name;
    EXPECT_GT(at_100, 5.0 * at_10) << c.name << ": the defect does not grow";
    const RunResult lie = find_integrator("rkmk4").integrate(bowl, every(1.0, 100.0, c.h));
    EXPECT_LT(rotation_defect(rotation_of(lie.final_state)), 1e-13);
  }
}

}  // namespace
}  // namespace rb

// The discrete-gradient method dg2 (docs/model.md, "A discrete-gradient
// method"): the energy's gradient against central differences, grad H . F = 0
// on and off SO(3), one step's energy and its step back, the energy at
// rounding over 10^6 steps where an explicit method's is not, the
// reversibility defect. Its order is measured with every other fixed-step
// method's by the registry-wide test (test_registry_order.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bench/lib/drift.hpp"
#include "bench/lib/reversibility.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/newton.hpp"
#include "problems/energy.hpp"
#include "problems/so3.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

// The states the gradient is checked at: the scene's start with R turned,
// and the same with R moved off SO(3) (the flat view reads any matrix)
struct Probe {
  const char* scene;
  bool off_group;
};

FlatState probe_state(const Probe& probe) {
  const Problem& p = testing::shipped_scene(probe.scene);
  FlatState y = p.y0();
  Mat3 R = so3_exp(Vec3(0.3, -0.2, 0.5)) * rotation_of(y);
  if (probe.off_group) R += 0.05 * Mat3{{0.3, -0.1, 0.2}, {0.0, 0.4, -0.3}, {0.1, 0.2, -0.2}};
  set_rotation(y, R);
  y[kOffsetAlpha] += 0.05;  // off the start's symmetric point
  return y;
}

TEST(DiscreteGradient, EnergyGradientMatchesCentralDifferencesAndIsNormalToF) {
  for (const Probe probe : {Probe{"valley-sideways", false}, Probe{"chaplygin-valley", false},
                            Probe{"chaplygin-valley", true}, Probe{"paraboloid-chaplygin", true}}) {
    SCOPED_TRACE(std::string(probe.scene) + (probe.off_group ? " off SO(3)" : ""));
    const Problem& p = testing::shipped_scene(probe.scene);
    const RollingBall& ball = p.model();
    const FlatState y = probe_state(probe);
    FlatState grad;
    const double H = flat_energy(ball, y, &grad);
    if (!probe.off_group) {
      EXPECT_NEAR(H, ball.derived(y).energy, 1e-15 * std::abs(H));
    }
    for (int k = 0; k < kFlatSize; ++k) {
      const double e = 1e-6 * (1.0 + std::abs(y[k]));
      FlatState up = y, down = y;
      up[k] += e;
      down[k] -= e;
      const double fd = (flat_energy(ball, up) - flat_energy(ball, down)) / (2 * e);
      EXPECT_NEAR(grad[k], fd, 1e-7 * (1.0 + std::abs(fd))) << "component " << k;
    }
    // R feeds back where the ball is anisotropic: its R part is not zero
    EXPECT_EQ(grad.head<9>().norm() > 0.0, ball.anisotropic());
    // H is a first integral of the flat field, on SO(3) and off it:
    // grad H . F = 0 to rounding (the ball off SO(3) is a ball with another
    // inertia, docs/model.md), so F = S grad H
    FlatState F;
    p.flat_rhs(y.data(), F.data());
    const double products = (grad.cwiseProduct(F)).cwiseAbs().sum();
    EXPECT_GT(products, 1e-3);
    EXPECT_LT(std::abs(grad.dot(F)), 1e-14 * products);
  }
}

TEST(DiscreteGradient, OneStepKeepsTheEnergyAndTheStepBackUndoesIt) {
  // one step of h = 0.1 moves the state by ~1e-1 and rk2's energy by 1e-4..1e-3
  for (const char* scene : {"valley-sideways", "chaplygin-valley"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const Integrator& dg = find_integrator("dg2");
    const RunResult there = dg.integrate(p, testing::fixed(0.1, 0.1));
    ASSERT_EQ(there.status, Status::ok) << there.message;
    const double scale = energy_scale(p), H0 = flat_energy(p.model(), p.y0());
    EXPECT_GT((there.final_state - p.y0()).norm(), 1e-2);
    EXPECT_LT(std::abs(flat_energy(p.model(), there.final_state) - H0), 1e-15 * scale);
    const RunResult rk2 = find_integrator("midpoint").integrate(p, testing::fixed(0.1, 0.1));
    EXPECT_GT(std::abs(flat_energy(p.model(), rk2.final_state) - H0), 1e-6 * scale);
    // symmetric: the step back with -h from where the step ended
    const Problem back(p.name(), p.model(), time_reversed(there.final_state), 0.1);
    const RunResult returned = dg.integrate(back, testing::fixed(0.1, 0.1));
    ASSERT_EQ(returned.status, Status::ok) << returned.message;
    EXPECT_LT((time_reversed(returned.final_state) - p.y0()).norm(), 1e-13 * (1.0 + p.y0().norm()));
  }
}

// The largest energy error over a run's outputs, relative to the scene's scale
double energy_error(const Problem& p, const RunResult& r) {
  return largest_drift(p, r.output).energy / energy_scale(p);
}

TEST(DiscreteGradient, EnergyStaysAtRoundingOverAMillionStepsWhereMidpointsDoesNot) {
  // paraboloid (homogeneous ball, integrable) at h = 0.01 to t = 10^4:
  // 10^6 steps. What is left is rounding: H's evaluation at a new point is
  // off by a few ulps of H (~1e-15 of the scale a step), and the steps'
  // errors add as a random walk, 1.1e-12 after 10^6 steps (measured: see
  // docs/integrators.md); the explicit midpoint rule's is ~1e-5. Under
  // AddressSanitizer (10x slower) the run is cut to 10^5 steps so that the
  // file stays well under ctest's 900 s; the bound is the same.
#if defined(__SANITIZE_ADDRESS__)
  constexpr double t_end = 1e3;
#else
  constexpr double t_end = 1e4;
#endif
  const Problem& p = testing::shipped_scene("paraboloid");
  const RunOptions o = testing::every(t_end / 100, t_end, 0.01);
  const RunResult dg = find_integrator("dg2").integrate(p, o);
  ASSERT_EQ(dg.status, Status::ok) << dg.message;
  EXPECT_EQ(dg.cost.steps, std::lround(t_end / 0.01));
  EXPECT_EQ(dg.cost.newton_failures, 0);
  const double dg_error = energy_error(p, dg);
  EXPECT_LT(dg_error, 5e-12);
  const RunResult rk2 = find_integrator("midpoint").integrate(p, o);
  ASSERT_EQ(rk2.status, Status::ok) << rk2.message;
  EXPECT_GT(energy_error(p, rk2), 1e-8);
  std::printf("energy error over %ld steps: dg2 %.2e, midpoint %.2e; newton iterations a step %.2f\n", dg.cost.steps,
              dg_error, energy_error(p, rk2), static_cast<double>(dg.cost.newton_iterations) / dg.cost.steps);
}

TEST(DiscreteGradient, EnergyAtRoundingWhereRFeedsBack) {
  // the anisotropic ball: H depends on R, and R leaves SO(3) by the
  // method's error (it keeps no quadratic invariant), yet H is kept: the
  // skew form holds for the flat field off SO(3) too. gauss2 at the same h,
  // symmetric but no discrete gradient, does not keep it.
  const Problem& p = testing::shipped_scene("chaplygin-bowl");
  const RunOptions o = testing::every(1.0, 100.0, 0.01);
  const RunResult dg = find_integrator("dg2").integrate(p, o);
  ASSERT_EQ(dg.status, Status::ok) << dg.message;
  EXPECT_LT(energy_error(p, dg), 1e-13);
  EXPECT_GT(largest_drift(p, dg.output).rotation_defect, 1e-8);
  const RunResult gauss2 = find_integrator("gauss2").integrate(p, o);
  ASSERT_EQ(gauss2.status, Status::ok) << gauss2.message;
  EXPECT_GT(energy_error(p, gauss2), 1e-8);
}

TEST(DiscreteGradient, ReversibilityDefectIsAtRoundingAndCostIsCounted) {
  for (const char* scene : {"valley-sideways", "chaplygin-valley"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const Integrator& dg = find_integrator("dg2");
    const ReversibilityDefect d = reversibility_defect(dg, p, testing::fixed(0.02, 1.0));
    ASSERT_EQ(d.status, Status::ok) << d.message;
    EXPECT_LT(d.worst(), 1e-12);
    const ReversibilityDefect rk2 = reversibility_defect(find_integrator("midpoint"), p, testing::fixed(0.02, 1.0));
    EXPECT_GT(rk2.worst(), 1e-8);
    // one Jacobian a step; every iteration but the first evaluates F at the midpoint
    const RunResult r = dg.integrate(p, testing::fixed(0.05, 1.0));
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_TRUE(dg.needs_jacobian());
    EXPECT_EQ(dg.info().newton_tol, kNewtonTol);
    EXPECT_EQ(r.cost.steps, 20);
    EXPECT_EQ(r.cost.jacobian_evals, 20);
    EXPECT_GE(r.cost.newton_iterations, 2 * 20);
    // (measured 12.75 a step on chaplygin-valley, 5 on valley-sideways)
    EXPECT_LE(r.cost.newton_iterations, 16 * 20);
    EXPECT_EQ(r.cost.rhs_evals, r.cost.newton_iterations - 20);
    EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals + 2);
    // rhs-equivalents: the 14 columns of each Jacobian, H(y0) a step and two
    // passes (H and its gradient, H at the end) an iteration after the first,
    // a 14 x 14 LU a step and a solve an iteration, 392 operations to one
    EXPECT_EQ(r.cost.jacobian_columns, 14 * 20);
    EXPECT_EQ(r.cost.model_passes, 20 + 2 * (r.cost.newton_iterations - 20));
    EXPECT_EQ(r.cost.lu_decompositions, 20);
    const double flops = 20 * (2.0 / 3.0 * 14 * 14 * 14) + r.cost.newton_iterations * (2.0 * 14 * 14);
    EXPECT_NEAR(r.cost.linear_algebra_flops, flops, 1e-12 * flops);  // (summed in another order)
    EXPECT_DOUBLE_EQ(r.cost.rhs_equivalents(),
                     static_cast<double>(r.cost.rhs_evals + r.cost.jacobian_columns + r.cost.model_passes) +
                         r.cost.linear_algebra_flops / 392.0);
  }
}

// The flat H (the energy of a ball whose inertia R's drift off SO(3) has
// deformed) against H at the nearest rotation, the real ball's
// (docs/model.md, "How the energy error is measured"): dg2 keeps the first
// to rounding while the second moves where R feeds back; rk4's second is
// larger than its first; a Lie-group method's two agree to rounding.
TEST(DiscreteGradient, FlatEnergyHidesTheDriftThatTheNearestRotationShows) {
  struct Energies {
    double flat, on_group, defect;
  };
  const auto energies = [](const Problem& p, const char* name, double h) {
    const RunResult r = find_integrator(name).integrate(p, testing::every(0.05, 3.0, h));
    EXPECT_EQ(r.status, Status::ok) << name << ": " << r.message;
    const Drift d = largest_drift(p, r.output);
    const double H0 = std::abs(p.model().derived(p.y0()).energy);
    return Energies{d.energy / H0, d.energy_on_group / H0, d.rotation_defect};
  };
  const Problem& plane = testing::shipped_scene("chaplygin-plane");  // measured: flat, at the nearest rotation
  const Energies dg = energies(plane, "dg2", 1.0 / 64);              // 1.7e-15, 2.9e-8
  EXPECT_LT(dg.flat, 1e-13);
  EXPECT_GT(dg.on_group, 1e-8);
  EXPECT_GT(dg.defect, 1e-8);
  const Energies rk4 = energies(plane, "rk4", 1.0 / 64);  // 4.2e-9, 3.3e-6
  EXPECT_GT(rk4.on_group, 100.0 * rk4.flat);
  const Energies rkmk4 = energies(plane, "rkmk4", 1.0 / 64);  // 2.1e-9 both
  EXPECT_NEAR(rkmk4.on_group, rkmk4.flat, 1e-13);
  EXPECT_GT(rkmk4.flat, 1e-10);
  // where the ball spins in a valley: dg2 6e-14 and 2.3e-3
  const Problem& valley = testing::shipped_scene("chaplygin-valley");
  const Energies dg_valley = energies(valley, "dg2", 1.0 / 64);
  EXPECT_LT(dg_valley.flat, 1e-12);
  EXPECT_GT(dg_valley.on_group, 1e-4);
  // the homogeneous ball's H does not read R: one number
  const Problem& bowl = testing::shipped_scene("bowl-3d");
  const Energies dg_bowl = energies(bowl, "dg2", 1.0 / 64);
  EXPECT_EQ(dg_bowl.on_group, dg_bowl.flat);
  EXPECT_LT(dg_bowl.flat, 1e-13);
}

// dg2's limits (docs/model.md, "What it does not keep"): its skew form is
// built from F and grad H, not from the system's structure, and moves the
// integrals linear in v whose rate is identically 0 in F, which every other
// method keeps exactly: v on a horizontal plane (an anisotropic ball), v_z
// in a spherical bowl. The drift falls at order 2 with h.
TEST(DiscreteGradient, SkewFormMovesTheLinearIntegralsAtOrderTwo) {
  // the largest |v - v0| / |v0| (all of v, or v_z) over outputs every 0.05 s to t = 3
  const auto drift = [](const Problem& p, const char* name, double h, bool only_z) {
    const RunResult r = find_integrator(name).integrate(p, testing::every(0.05, 3.0, h));
    EXPECT_EQ(r.status, Status::ok) << name << ": " << r.message;
    const Vec3 v0 = momentum_of(p.y0());
    double largest = 0.0;
    for (const FlatState& y : r.output.y) {
      const Vec3 dv = momentum_of(y) - v0;
      largest = std::max(largest, (only_z ? std::abs(dv.z()) : dv.norm()) / v0.norm());
    }
    return largest;
  };
  struct Case {
    const char* scene;
    bool only_z;
    double at_coarsest;  // measured: 4.8e-7 on the plane, 4.2e-7 in the bowl at h = 1/256
  };
  for (const Case c : {Case{"chaplygin-plane", false, 4.8e-7}, Case{"bowl-3d", true, 4.2e-7}}) {
    SCOPED_TRACE(c.scene);
    const Problem& p = testing::shipped_scene(c.scene);
    double before = 0.0;
    for (const double h : {1.0 / 256, 1.0 / 512, 1.0 / 1024}) {
      const double d = drift(p, "dg2", h, c.only_z);
      if (before == 0.0) {
        EXPECT_GT(d, 0.5 * c.at_coarsest);
        EXPECT_LT(d, 2.0 * c.at_coarsest);
      } else {
        EXPECT_GT(before / d, 3.5) << "h = " << h;  // order 2: a quarter per halving
        EXPECT_LT(before / d, 4.5) << "h = " << h;
      }
      before = d;
    }
    // every other kind of method keeps it exactly, Euler included
    for (const char* other : {"euler", "rk4", "rkmk4", "gauss2", "lie-gauss2", "dla2"})
      EXPECT_LT(drift(p, other, 1.0 / 256, c.only_z), 1e-13) << other;
  }
}

}  // namespace
}  // namespace rb

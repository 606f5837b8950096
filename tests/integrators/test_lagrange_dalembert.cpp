// The discrete Lagrange-d'Alembert method dla2 (docs/model.md, "A discrete
// Lagrange-d'Alembert method"): its momenta against the discrete Lagrangian's
// derivatives on the rolling distribution, the step back undoes the step, R stays on
// SO(3), the reversibility defect at rounding, the Newton's counts, the
// discrete momentum it keeps on a plane (and with it Chaplygin's integrals),
// and its energy over a long run on the paraboloid. Its order is measured
// with every other fixed-step method's by the registry-wide test
// (test_registry_order.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/lib/drift.hpp"
#include "bench/lib/reversibility.hpp"
#include "integrators/registry.hpp"
#include "integrators/steppers/newton.hpp"
#include "problems/so3.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

TEST(LagrangeDalembert, TheStepBackUndoesTheStepAndRStaysARotation) {
  // symmetric: from the step's end, v negated, one step of the same h comes
  // back to the start with v negated (Phi_h^-1 = rho Phi_h rho); one step of
  // 0.1 moves the state by ~1e-1, so the test can fail
  for (const char* scene : {"valley-sideways", "chaplygin-valley", "paraboloid-chaplygin"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const Integrator& dla = find_integrator("dla2");
    const RunResult there = dla.integrate(p, testing::fixed(0.1, 0.1));
    ASSERT_EQ(there.status, Status::ok) << there.message;
    EXPECT_GT((there.final_state - p.y0()).norm(), 1e-2);
    const Problem back(p.name(), p.model(), time_reversed(there.final_state), 0.1);
    const RunResult returned = dla.integrate(back, testing::fixed(0.1, 0.1));
    ASSERT_EQ(returned.status, Status::ok) << returned.message;
    EXPECT_LT((time_reversed(returned.final_state) - p.y0()).norm(), 1e-13 * (1.0 + p.y0().norm()));
    EXPECT_LT(rotation_defect(rotation_of(there.final_state)), 1e-14);
  }
}

// The discrete Lagrangian of docs/model.md at q0 = (R0, alpha0), q1 = (R1,
// alpha1), written here from its definition (not from the stepper's
// equations): phi = cay^-1(R0^T R1) = 2 vee(F - F^T) / (1 + tr F).
struct DiscreteLagrangian {
  const RollingBall& ball;
  double h;
  Vec3 theta_body;

  Vec3 centre(const Vec2& a) const {
    const double z[kZSize] = {0.0, 0.0, 0.0, a[0], a[1]};
    const Kinematics<double> k = ball.kinematics<false>(Mat3::Identity().eval(), z);
    return Vec3(a[0], a[1], ball.landscape().height(a[0], a[1])) + ball.params().radius * k.N;
  }
  double operator()(const Mat3& R0, const Vec2& a0, const Mat3& R1, const Vec2& a1) const {
    const Mat3 F = R0.transpose() * R1;
    const Vec3 phi = 2.0 * Vec3(F(2, 1) - F(1, 2), F(0, 2) - F(2, 0), F(1, 0) - F(0, 1)) / (1.0 + F.trace());
    const Vec3 C0 = centre(a0), C1 = centre(a1);
    const double m = ball.params().mass, g0 = ball.params().gravity;
    return phi.dot(theta_body.cwiseProduct(phi)) / (2 * h) + m * (C1 - C0).squaredNorm() / (2 * h) -
           0.5 * h * m * g0 * (C0.z() + C1.z());
  }
  // (zeta, B zeta) in D at alpha: B zeta = r E^-1 C'^T (zeta x N)
  Vec2 along_d(const Vec2& a, const Vec3& zeta) const {
    const double z[kZSize] = {0.0, 0.0, 0.0, a[0], a[1]};
    const Kinematics<double> k = ball.kinematics<false>(Mat3::Identity().eval(), z);
    return ball.params().radius * k.E.inverse() * k.C_d.transpose() * zeta.cross(k.N);
  }
};

TEST(LagrangeDalembert, ItsMomentaAreTheDiscreteLagrangiansDerivativesOnTheDistribution) {
  // the discrete Lagrange-d'Alembert principle, checked against L_d itself
  // by central differences: for a step (q0, v0) -> (q1, v1) of the method,
  // v0 = -D1 L_d and v1 = D2 L_d on D (along (zeta, B zeta), zeta = e_i,
  // R turned by exp(eps hat(zeta))), and the pair satisfies the discrete
  // rolling constraint; on a general landscape and where R feeds back
  for (const char* scene : {"valley-sideways", "paraboloid-chaplygin", "gaussian-hills-chaplygin"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const RollingBall& ball = p.model();
    const double h = 0.05, m = ball.params().mass, r = ball.params().radius;
    const RunResult step = find_integrator("dla2").integrate(p, testing::fixed(h, h));
    ASSERT_EQ(step.status, Status::ok) << step.message;
    const FlatState &y0 = p.y0(), &y1 = step.final_state;
    const Mat3 R0 = rotation_of(y0), R1 = rotation_of(y1);
    const Vec2 a0 = contact_of(y0), a1 = contact_of(y1);
    const DiscreteLagrangian L{ball, h, ball.params().inertia.value_or(Vec3::Constant(0.4 * m * r * r))};
    const double eps = 1e-6;
    Vec3 d1, d2;
    for (int i = 0; i < 3; ++i) {
      const Vec3 e = Vec3::Unit(i);
      const Vec2 b0 = L.along_d(a0, e), b1 = L.along_d(a1, e);
      d1[i] = (L(so3_exp(eps * e) * R0, a0 + eps * b0, R1, a1) - L(so3_exp(-eps * e) * R0, a0 - eps * b0, R1, a1)) /
              (2 * eps);
      d2[i] = (L(R0, a0, so3_exp(eps * e) * R1, a1 + eps * b1) - L(R0, a0, so3_exp(-eps * e) * R1, a1 - eps * b1)) /
              (2 * eps);
    }
    const Vec3 v0 = momentum_of(y0), v1 = momentum_of(y1);
    EXPECT_GT((v1 - v0).norm(), 1e-4 * v0.norm());
    EXPECT_LT((-d1 - v0).norm(), 1e-7 * v0.norm()) << (-d1).transpose() << " vs " << v0.transpose();
    EXPECT_LT((d2 - v1).norm(), 1e-7 * v1.norm()) << d2.transpose() << " vs " << v1.transpose();
    // the discrete constraint: C'(a0)^T (dC - r theta x N0) + C'(a1)^T (dC - r theta x N1) = 0
    const double z0[kZSize] = {0.0, 0.0, 0.0, a0[0], a0[1]}, z1[kZSize] = {0.0, 0.0, 0.0, a1[0], a1[1]};
    const Kinematics<double> k0 = ball.kinematics<false>(Mat3::Identity().eval(), z0);
    const Kinematics<double> k1 = ball.kinematics<false>(Mat3::Identity().eval(), z1);
    const Mat3 F = R0.transpose() * R1;
    const Vec3 theta = R0 * (2.0 * Vec3(F(2, 1) - F(1, 2), F(0, 2) - F(2, 0), F(1, 0) - F(0, 1)) / (1.0 + F.trace()));
    const Vec3 dC = L.centre(a1) - L.centre(a0);
    const Vec2 slip =
        k0.C_d.transpose() * (dC - r * theta.cross(k0.N)) + k1.C_d.transpose() * (dC - r * theta.cross(k1.N));
    EXPECT_LT(slip.norm(), 1e-14 * (1.0 + dC.norm() / r) * r);
    EXPECT_GT(dC.norm(), 1e-3 * r);
  }
}

TEST(LagrangeDalembert, ReversibilityDefectIsAtRoundingAndCostIsCounted) {
  for (const char* scene : {"valley-sideways", "chaplygin-valley"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const Integrator& dla = find_integrator("dla2");
    const ReversibilityDefect d = reversibility_defect(dla, p, testing::fixed(0.02, 1.0));
    ASSERT_EQ(d.status, Status::ok) << d.message;
    EXPECT_LT(d.worst(), 1e-12);
    const ReversibilityDefect rk2 = reversibility_defect(find_integrator("midpoint"), p, testing::fixed(0.02, 1.0));
    EXPECT_GT(rk2.worst(), 1e-8);
    // one AD Jacobian of the residual a step; one evaluation of the model a
    // step, at its end (the step's stage, checked against the limits)
    const RunResult r = dla.integrate(p, testing::fixed(0.05, 1.0));
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_TRUE(dla.needs_jacobian());
    EXPECT_TRUE(dla.info().on_group);
    EXPECT_EQ(dla.info().newton_tol, kNewtonTol);
    EXPECT_EQ(r.cost.steps, 20);
    EXPECT_EQ(r.cost.jacobian_evals, 20);
    EXPECT_EQ(r.cost.rhs_evals, 20);
    EXPECT_EQ(r.cost.exp_evals, 20);
    EXPECT_EQ(r.cost.validity_checks, r.cost.rhs_evals + 2);
    EXPECT_GE(r.cost.newton_iterations, 2 * 20);
    EXPECT_LE(r.cost.newton_iterations, 12 * 20);
    EXPECT_EQ(r.cost.newton_failures, 0);
    // its cost in rhs-equivalents (docs/formats.md, rhs_equivalents): 1 rhs a
    // step, plus the Jacobian's 5 columns, a geometry pass at the start, at
    // the end and in every iteration after the first (whose residual the AD
    // pass gave), and a 5 x 5 LU a step and a solve an iteration at 392
    // operations to one
    const long n = r.cost.newton_iterations;
    EXPECT_EQ(r.cost.jacobian_columns, 5 * 20);
    EXPECT_EQ(r.cost.model_passes, 2 * 20 + (n - 20));
    EXPECT_EQ(r.cost.lu_decompositions, 20);
    const double flops = 20 * (2.0 / 3.0 * 125.0) + n * 50.0;
    EXPECT_NEAR(r.cost.linear_algebra_flops, flops, 1e-12 * flops);  // (summed in another order)
    const double per_step = r.cost.rhs_equivalents() / 20.0;
    const double expected = (20.0 + 5 * 20 + 2 * 20 + (n - 20) + flops / 392.0) / 20.0;
    EXPECT_NEAR(per_step, expected, 1e-12 * expected);
    EXPECT_GT(per_step, 6.0 * r.cost.rhs_evals / 20.0);  // far above its 1 rhs a step
    std::printf(
        "%s: reversibility %.2e (midpoint %.2e), newton iterations a step %.2f, rhs-equivalents a step "
        "%.2f\n",
        scene, d.worst(), rk2.worst(), static_cast<double>(n) / r.cost.steps, per_step);
  }
}

TEST(LagrangeDalembert, OnAPlaneItKeepsTheMomentumAndChaplyginsIntegralsButNotTheEnergy) {
  // N constant and N x g = 0: the update gives v1 = v0 exactly (the
  // discrete momentum of the plane's horizontal symmetries), and with R a
  // rotation to rounding M . M = |v|^2 and M . gamma = v . N stay at
  // rounding; the explicit midpoint rule keeps v too (v' = 0) but its R
  // drifts, and M . M with it. The energy is no discrete invariant: it
  // oscillates at O(h^2) (measured 2.1e-5 of the scale at h = 1/128, 10^4 steps).
  const Problem& p = testing::shipped_scene("chaplygin-plane");
  const RunOptions o = testing::every(10000.0 / 128 / 100, 10000.0 / 128, 1.0 / 128);
  const RunResult dla = find_integrator("dla2").integrate(p, o);
  ASSERT_EQ(dla.status, Status::ok) << dla.message;
  const InvariantMeter invariants(p);
  ASSERT_EQ(invariants.names().size(), 2u);
  double worst = 0.0;
  for (const FlatState& y : dla.output.y) {
    EXPECT_EQ(momentum_of(y), momentum_of(p.y0()));
    for (const double e : invariants.errors(y)) worst = std::max(worst, e);
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(largest_drift(p, dla.output).rotation_defect, 1e-13);
  const double energy = largest_drift(p, dla.output).energy / energy_scale(p);
  EXPECT_GT(energy, 1e-6);
  EXPECT_LT(energy, 1e-4);
  const RunResult rk2 = find_integrator("midpoint").integrate(p, o);
  ASSERT_EQ(rk2.status, Status::ok) << rk2.message;
  double rk2_worst = 0.0;
  for (const FlatState& y : rk2.output.y)
    for (const double e : invariants.errors(y)) rk2_worst = std::max(rk2_worst, e);
  EXPECT_GT(rk2_worst, 1e-4);
}

// The largest relative energy error over the first and the second half of a
// run's outputs
struct Halves {
  double first = 0.0, second = 0.0;
};

Halves energy_halves(const Problem& p, const RunResult& r) {
  const DriftMeter meter(p);
  Halves h;
  const std::size_t n = r.output.y.size();
  for (std::size_t i = 0; i < n; ++i) {
    double& half = i < n / 2 ? h.first : h.second;
    half = std::max(half, meter.at(r.output.y[i]).energy / energy_scale(p));
  }
  return h;
}

TEST(LagrangeDalembert, EnergyErrorIsBoundedOverALongRunOnTheParaboloid) {
  // 10^5 steps at h = 1/128 (t = 781), the ladder's first rung with both
  // balls: the energy error oscillates with an amplitude that does not grow
  // (second half's largest within 1 % of the first's on the homogeneous
  // ball, 3 % where R feeds back; measured 1.907e-4 / 1.908e-4 and 2.147e-4
  // / 2.204e-4), O(h^2) (4.00 times smaller at h / 2), where the explicit
  // midpoint rule's doubles from the first half to the second. It is larger
  // than gauss2's at the same h (4.1e-6 on the paraboloid): symmetric, both
  // bounded, the variational structure does not make it smaller.
  const double h = 1.0 / 128, t_end = 1e5 * h;
  const RunOptions o = testing::every(t_end / 100, t_end, h);
  for (const char* scene : {"paraboloid", "paraboloid-chaplygin"}) {
    SCOPED_TRACE(scene);
    const Problem& p = testing::shipped_scene(scene);
    const RunResult dla = find_integrator("dla2").integrate(p, o);
    ASSERT_EQ(dla.status, Status::ok) << dla.message;
    EXPECT_EQ(dla.cost.newton_failures, 0);
    const Halves e = energy_halves(p, dla);
    EXPECT_GT(e.first, 1e-5);
    EXPECT_LT(e.first, 5e-4);
    EXPECT_LT(e.second, 1.05 * e.first);
    EXPECT_GT(e.second, 0.95 * e.first);
  }
  const Problem& p = testing::shipped_scene("paraboloid");
  const Halves dla = energy_halves(p, find_integrator("dla2").integrate(p, o));
  const Halves half_h =
      energy_halves(p, find_integrator("dla2").integrate(p, testing::every(t_end / 100, t_end, h / 2)));
  EXPECT_NEAR(dla.first / half_h.first, 4.0, 0.2);
  const Halves gauss2 = energy_halves(p, find_integrator("gauss2").integrate(p, o));
  EXPECT_GT(dla.first, 10.0 * gauss2.first);
  const Halves rk2 = energy_halves(p, find_integrator("midpoint").integrate(p, o));
  EXPECT_GT(rk2.second, 1.8 * rk2.first);
}

}  // namespace
}  // namespace rb

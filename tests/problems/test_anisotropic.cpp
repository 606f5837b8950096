// The anisotropic (Chaplygin) ball of docs/model.md, "A ball whose orientation
// matters": T(R, alpha) and its Sherman-Morrison inverse, the closed forms on
// a plane and an incline, equal moments reducing to the homogeneous ball for
// every integrator, and R feeding back into the contact path.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::every;

// A scene text with the given landscape, inertia and start velocity.
Problem scene_with(const std::string& landscape, const nlohmann::json& inertia, const nlohmann::json& velocity,
                   double spin, double t_end) {
  nlohmann::json s = {
      {"name", "aniso"},
      {"landscape", landscape},
      {"ball", {{"radius", 0.1}, {"mass", 1.0}}},
      {"start",
       {{"contact", {0.2, -0.1}},
        {"velocity", velocity},
        {"spin", spin},
        {"orientation", {0.8775825618903728, 0.15980851286806766, 0.3196170257361353, 0.3196170257361353}}}},
      {"t_end", t_end}};
  if (!inertia.is_null()) s["ball"]["inertia"] = inertia;
  return make_problem(parse_scene(s.dump()));
}

TEST(Anisotropic, InverseOfTIsExactAtRandomStates) {
  const Problem p = make_problem(load_scene("chaplygin-valley"));
  ASSERT_TRUE(p.model().anisotropic());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 R = so3_exp(3.0 * Vec3(u(rng), u(rng), u(rng)));
    const Vec3 N = Vec3(u(rng), u(rng), 1.0 + u(rng) * 0.5).normalized();
    const Mat3 T = p.model().contact_inertia(R, N);
    Mat3 T_inv;
    for (int k = 0; k < 3; ++k) T_inv.col(k) = p.model().omega_from_momentum(R, N, Vec3::Unit(k));
    // T is ~1e-2 here and T^-1 ~1e2: the product is I to rounding, 1e-14
    EXPECT_LT((T_inv * T - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14) << "trial " << trial;
    const Vec3 w(u(rng), u(rng), u(rng));
    EXPECT_LT((p.model().omega_from_momentum(R, N, p.model().momentum_from_omega(R, N, w)) - w).norm(),
              1e-14 * w.norm());
  }
}

// With Theta = (2/5) m r^2 I every integrator runs the homogeneous ball: the
// same trajectory to rounding (1e-12 relative over 100 steps).
TEST(Anisotropic, EqualMomentsAreTheHomogeneousBallForEveryIntegrator) {
  const nlohmann::json velocity = {0.4, 0.3};
  const Problem homogeneous = scene_with("cos(x*pi + pi)/10 - y/10", nullptr, velocity, 2.0, 1.0);
  const Problem equal = scene_with("cos(x*pi + pi)/10 - y/10", {0.004, 0.004, 0.004}, velocity, 2.0, 1.0);
  EXPECT_FALSE(equal.model().anisotropic());
  EXPECT_LT((equal.y0() - homogeneous.y0()).norm(), 1e-16);
  int checked = 0;
  for (const auto& integrator : registry()) {
    RunOptions o = every(0.25, 1.0, 0.01);
    o.tolerances = Tolerances(1e-8, 1e-8);
    o.h = integrator->adaptive() ? 0.0 : 0.01;
    const RunResult a = integrator->integrate(homogeneous, o);
    const RunResult b = integrator->integrate(equal, o);
    ASSERT_EQ(a.status, Status::ok) << integrator->name() << ": " << a.message;
    ASSERT_EQ(b.output.y.size(), a.output.y.size()) << integrator->name();
    for (std::size_t i = 0; i < a.output.y.size(); ++i)
      EXPECT_LT((a.output.y[i] - b.output.y[i]).norm(), 1e-12 * (1.0 + a.output.y[i].norm()))
          << integrator->name() << " at t = " << a.output.t[i];
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

// On a horizontal plane v' = m r N x g = 0: v is constant and so is H, over
// 10^4 steps of rkmk4, while omega and the contact path turn with R.
TEST(Anisotropic, PlaneKeepsMomentumAndEnergyWhileThePathBends) {
  const Problem p = make_problem(load_scene("chaplygin-plane"));
  ASSERT_TRUE(p.model().anisotropic());
  const RunResult r = find_integrator("rkmk4").integrate(p, every(0.03, 3.0, 3e-4));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.cost.steps, 10'000);
  const Vec3 v0 = momentum_of(p.y0());
  const Derived d0 = p.model().derived(p.y0());
  double bend = 0.0, omega_change = 0.0;
  for (const FlatState& y : r.output.y) {
    EXPECT_LT((momentum_of(y) - v0).norm(), 1e-12 * v0.norm());
    const Derived d = p.model().derived(y);
    EXPECT_NEAR(d.energy, d0.energy, 1e-12 * std::abs(d0.energy));
    omega_change = std::max(omega_change, (d.omega - d0.omega).norm());
  }
  // the homogeneous ball with the same start moves on a straight line
  const Vec2 a0 = contact_of(p.y0());
  const Vec2 dir = (contact_of(r.output.y.front()) - a0).normalized();
  for (const FlatState& y : r.output.y) {
    const Vec2 d = contact_of(y) - a0;
    bend = std::max(bend, std::abs(d.x() * dir.y() - d.y() * dir.x()));
  }
  EXPECT_GT(omega_change, 0.1 * d0.omega.norm()) << "omega does not change with R";
  EXPECT_GT(bend, 1e-3) << "the contact path stays straight";
}

// On an incline f = -s y, v' = m r (N x g) is constant: v(t) = v0 + m r (N x g) t.
// The start velocity is given by its horizontal part and lifted onto the slope.
TEST(Anisotropic, InclineMomentumIsLinearInTime) {
  const double s = 0.3;
  const Problem p = scene_with("-0.3*y", {0.003, 0.004, 0.005}, {0.2, 0.1}, 4.0, 1.0);
  const Vec3 N = Vec3(0.0, s, 1.0).normalized();
  const Vec3 rate = p.model().params().mass * p.model().params().radius * N.cross(Vec3(0.0, 0.0, -9.81));
  const RunResult r = find_integrator("rkmk4").integrate(p, every(0.1, 1.0, 1e-3));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  for (std::size_t i = 0; i < r.output.y.size(); ++i)
    EXPECT_LT((momentum_of(r.output.y[i]) - (momentum_of(p.y0()) + rate * r.output.t[i])).norm(), 1e-10)
        << "t = " << r.output.t[i];
}

// The lifted start velocity is tangential and has the given horizontal part.
TEST(Anisotropic, HorizontalStartVelocityIsLiftedOntoTheTangentPlane) {
  const Problem p = scene_with("0.5*x^2 - 0.3*y", {0.003, 0.004, 0.005}, {0.2, 0.1}, 0.0, 1.0);
  const Derived d = p.model().derived(p.y0());
  EXPECT_NEAR(d.centre_velocity.x(), 0.2, 1e-14);
  EXPECT_NEAR(d.centre_velocity.y(), 0.1, 1e-14);
  EXPECT_NEAR(d.centre_velocity.dot(d.N), 0.0, 1e-14);
  EXPECT_NEAR(d.spin, 0.0, 1e-14);
}

// Where R feeds back, the Lie-group method and its classical twin differ in
// the contact point (for the homogeneous ball they agree to rounding, see
// test_munthe_kaas.cpp), and equal moments make them agree again.
TEST(Anisotropic, RkmkAndRkDifferWhereRFeedsBack) {
  const Problem p = make_problem(load_scene("chaplygin-valley"));
  const RunOptions o = testing::fixed(0.01, 2.0);
  const RunResult lie = find_integrator("rkmk4").integrate(p, o);
  const RunResult flat = find_integrator("rk4").integrate(p, o);
  ASSERT_EQ(lie.status, Status::ok) << lie.message;
  ASSERT_EQ(flat.status, Status::ok) << flat.message;
  EXPECT_GT((contact_of(lie.final_state) - contact_of(flat.final_state)).norm(), 1e-10);
}

// The normal force the validity check uses (F . N without omega') equals the
// derived one (the full contact force, with the gyroscopic term).
TEST(Anisotropic, CheapNormalForceEqualsTheFullContactForce) {
  for (const char* scene : {"chaplygin-valley", "chaplygin-bumpy-long", "valley-sideways", "bowl-3d"}) {
    const Problem p = make_problem(load_scene(scene));
    const RunResult r = find_integrator("rkmk4").integrate(p, every(0.1, 1.0, 1e-3));
    ASSERT_EQ(r.status, Status::ok) << scene << ": " << r.message;
    for (const FlatState& y : r.output.y) {
      const double full = p.model().derived(y).normal_force;
      EXPECT_NEAR(p.model().margins_at(y).normal_force, full, 1e-12 * std::abs(full)) << scene;
    }
  }
}

}  // namespace
}  // namespace rb

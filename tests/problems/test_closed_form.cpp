// docs/model.md's table "Results with a closed form", row by row, with the suite's
// own integrators, and the closed-form solutions of problems/exact.hpp
// against fine rkmk4 runs. Tolerances are stated where they are used; rkmk4
// with h = 1e-3 has a global error far below them (~1e-12 on these scenes),
// so they measure the model and the exact solutions, not the method.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "integrators/registry.hpp"
#include "problems/exact.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace rb {
namespace {

// Outputs every dt up to the problem's t_end.
RunOptions every(const Problem& problem, double dt, double h) {
  RunOptions o;
  o.h = h;
  const int n = static_cast<int>(std::lround(problem.t_end() / dt));
  for (int k = 1; k < n; ++k) o.output_times.push_back(k * dt);
  return o;
}

RunResult run(const Problem& problem, const char* method, double dt, double h) {
  const RunResult r = find_integrator(method).integrate(problem, every(problem, dt, h));
  EXPECT_EQ(r.status, Status::ok) << problem.name() << " with " << method << ": " << r.message;
  EXPECT_DOUBLE_EQ(r.stop_time, problem.t_end());
  return r;
}

Vec3 omega_of(const Problem& p, const FlatState& y) { return p.model().derived(y).omega; }

// The flat state of an exact solution (v = T omega at the exact contact).
FlatState flat_of(const Problem& p, const ExactState& e) {
  const Vec3 N = p.model().normal_at(e.alpha.x(), e.alpha.y());
  return make_flat(e.R, p.model().momentum_from_omega(e.R, N, e.omega), e.alpha);
}

TEST(ClosedForm, PlaneIsAStraightLineWithRotationExpOfOmega) {
  const Problem p = make_problem(load_scene("plane"));
  ASSERT_NE(p.exact(), nullptr);
  const Vec3 omega0 = omega_of(p, p.y0());
  const Mat3 R0 = rotation_of(p.y0());
  const RunResult r = run(p, "rkmk4", 0.1, 0.01);
  for (std::size_t i = 0; i < r.output.t.size(); ++i) {
    const double t = r.output.t[i];
    const FlatState& y = r.output.y[i];
    const ExactState e = p.exact()->at(t);
    ASSERT_TRUE(e.has_rotation);
    // R(t) = exp(t hat(omega0)) R0, to rounding over 200 steps: 1e-12
    EXPECT_LT((rotation_of(y) - so3_exp(t * omega0) * R0).norm(), 1e-12) << "t = " << t;
    EXPECT_LT((e.R - so3_exp(t * omega0) * R0).norm(), 1e-14);
    // the contact moves linearly and omega is constant: rounding only
    EXPECT_LT((contact_of(y) - e.alpha).norm(), 1e-13) << "t = " << t;
    EXPECT_LT((omega_of(p, y) - omega0).norm(), 1e-13);
    EXPECT_LT((e.omega - omega0).norm(), 1e-15);
  }
  // the start's spin 1.5 is about the normal e_z; the centre moves at u0
  EXPECT_NEAR(omega0.z(), 1.5, 1e-15);
}

TEST(ClosedForm, InclineCentreAcceleratesAtFiveSeventhsGSinTheta) {
  const Scene scene = load_scene("incline-spin");
  const Problem p = make_problem(scene);
  const auto& exact = dynamic_cast<const InclineSolution&>(*p.exact());
  const double s = scene.params.at("s"), g0 = scene.gravity;
  const double theta = std::atan(s);
  // the exact solution's own acceleration: (5/7) g0 sin(theta) down the fall line (0, 1, -s)
  const Vec3 fall = Vec3(0.0, 1.0, -s).normalized();
  EXPECT_LT((exact.centre_acceleration() - (5.0 / 7.0) * g0 * std::sin(theta) * fall).norm(), 1e-14);
  EXPECT_FALSE(exact.has_rotation());  // the spin turns the rotation axis

  const double dt = 0.1;
  const RunResult r = run(p, "rkmk4", dt, 1e-3);
  std::vector<Vec3> c;
  for (const FlatState& y : r.output.y) c.push_back(p.model().derived(y).centre);
  // alpha is quadratic in t here, which RK4 integrates exactly: rounding only
  for (std::size_t i = 0; i < c.size(); ++i)
    EXPECT_LT((c[i] - exact.centre_at(r.output.t[i])).norm(), 1e-12) << "t = " << r.output.t[i];
  // second differences of the integrated centre give its acceleration to 1e-9
  for (std::size_t i = 1; i + 1 < c.size(); ++i) {
    const Vec3 a = (c[i + 1] - 2.0 * c[i] + c[i - 1]) / (dt * dt);
    EXPECT_NEAR(a.dot(fall), (5.0 / 7.0) * g0 * std::sin(theta), 1e-9);
    EXPECT_LT((a - a.dot(fall) * fall).norm(), 1e-9);
  }
  // s = omega . N is constant on a plane: 1e-12
  for (const FlatState& y : r.output.y) EXPECT_NEAR(p.model().derived(y).spin, 2.0, 1e-12);
}

TEST(ClosedForm, InclineWithAFixedAxisHasAnExactRotation) {
  // omega0 parallel to N x g: the ball rolls straight down, the axis is fixed
  Scene scene = load_scene("incline-spin");
  scene.start.velocity = Vec3(0.0, 0.4, -0.08);  // down the fall line (0, 1, -s)
  scene.start.spin = 0.0;
  const Problem p = make_problem(scene);
  const auto& exact = dynamic_cast<const InclineSolution&>(*p.exact());
  ASSERT_TRUE(exact.has_rotation());
  const RunResult r = run(p, "rkmk4", 0.1, 1e-3);
  for (std::size_t i = 0; i < r.output.t.size(); ++i) {
    const ExactState e = exact.at(r.output.t[i]);
    // R from the Lie-group method: its truncation error only, 1e-10
    EXPECT_LT(rotation_angle_between(e.R, rotation_of(r.output.y[i])), 1e-10) << "t = " << r.output.t[i];
    EXPECT_LT((contact_of(r.output.y[i]) - e.alpha).norm(), 1e-12);
  }
}

// Times where the contact's signed distance along the swing direction
// crosses 0, from cubic interpolation through 4 dense outputs.
std::vector<double> zero_crossings(const std::vector<double>& t, const std::vector<double>& s) {
  std::vector<double> out;
  for (std::size_t i = 1; i + 2 < s.size(); ++i) {
    if ((s[i] < 0.0) == (s[i + 1] < 0.0)) continue;
    // Lagrange cubic through i-1..i+2, solved by Newton from the linear guess
    const double* T = &t[i - 1];
    const double* S = &s[i - 1];
    auto p = [&](double x) {
      double sum = 0.0;
      for (int a = 0; a < 4; ++a) {
        double w = S[a];
        for (int b = 0; b < 4; ++b)
          if (b != a) w *= (x - T[b]) / (T[a] - T[b]);
        sum += w;
      }
      return sum;
    };
    double x = t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i]);
    for (int it = 0; it < 20; ++it) {
      const double d = 1e-7;
      x -= p(x) * 2.0 * d / (p(x + d) - p(x - d));
    }
    out.push_back(x);
  }
  return out;
}

TEST(ClosedForm, BowlPendulumPeriodIsFourKOverW0) {
  const Scene scene = load_scene("bowl-planar");
  const Problem p = make_problem(scene);
  const auto& exact = dynamic_cast<const BowlPendulumSolution&>(*p.exact());
  const double rho = scene.params.at("rho"), r = scene.ball.radius, g0 = scene.gravity;
  const double theta0 = std::numbers::pi / 6.0;
  EXPECT_NEAR(exact.theta0(), theta0, 1e-15);
  const double period = bowl_period(rho, r, g0, theta0);
  EXPECT_DOUBLE_EQ(exact.period(), period);
  // small-amplitude check of the formula: 2 pi / w0 (1 + theta0^2 / 16 + ...)
  const double w0 = std::sqrt(5.0 * g0 / (7.0 * (rho - r)));
  EXPECT_NEAR(period, 2.0 * std::numbers::pi / w0 * (1.0 + theta0 * theta0 / 16.0), 1e-3 * period);
  EXPECT_NEAR(bowl_period(rho, r, g0, 1e-8), 2.0 * std::numbers::pi / w0, 1e-12);

  const RunResult run_ = run(p, "rkmk4", 1e-3, 1e-3);
  std::vector<double> t = {0.0}, s = {contact_of(p.y0()).dot(exact.direction())};
  for (std::size_t i = 0; i < run_.output.t.size(); ++i) {
    t.push_back(run_.output.t[i]);
    s.push_back(contact_of(run_.output.y[i]).dot(exact.direction()));
  }
  const std::vector<double> zeros = zero_crossings(t, s);
  ASSERT_GE(zeros.size(), 4u);
  // crossings at T/4, 3T/4, 5T/4, ...: relative 1e-6 of the period
  for (std::size_t k = 0; k < zeros.size(); ++k)
    EXPECT_NEAR(zeros[k], (2.0 * k + 1.0) * period / 4.0, 1e-6 * period) << "crossing " << k;
  EXPECT_NEAR(zeros[2] - zeros[0], period, 1e-6 * period);
  // the motion stays in the vertical plane through e
  for (const FlatState& y : run_.output.y) {
    const Vec2 a = contact_of(y);
    EXPECT_LT(std::abs(a.x() * exact.direction().y() - a.y() * exact.direction().x()), 1e-12);
  }
}

TEST(ClosedForm, BowlNormalForceIsSeventeenCosMinusTenCos0) {
  const Scene scene = load_scene("bowl-planar");
  const Problem p = make_problem(scene);
  const auto& exact = dynamic_cast<const BowlPendulumSolution&>(*p.exact());
  const double m = scene.ball.mass, g0 = scene.gravity, rho = scene.params.at("rho");
  const double theta0 = exact.theta0();
  // along an rkmk4 run, with theta from the integrated contact: 1e-9 of m g0
  const RunResult r = run(p, "rkmk4", 0.01, 1e-3);
  for (std::size_t i = 0; i < r.output.t.size(); ++i) {
    const double theta = std::asin(contact_of(r.output.y[i]).norm() / rho);
    EXPECT_NEAR(p.model().derived(r.output.y[i]).normal_force, bowl_normal_force(m, g0, theta, theta0), 1e-9 * m * g0)
        << "t = " << r.output.t[i];
  }
  // at the exact state, with the exact theta(t): 1e-11 of m g0
  for (double t = 0.0; t < 5.0; t += 0.05) {
    const Derived d = p.model().derived(flat_of(p, exact.at(t)));
    EXPECT_NEAR(d.normal_force, bowl_normal_force(m, g0, exact.theta(t), theta0), 1e-11 * m * g0) << "t = " << t;
  }
  // at the start (rest) it is m g0 cos(theta0), at the bottom m g0 (17 - 10 cos(theta0)) / 7
  EXPECT_NEAR(bowl_normal_force(m, g0, theta0, theta0), m * g0 * std::cos(theta0), 1e-14);
}

TEST(ClosedForm, BowlPendulumExactSolutionIsConsistent) {
  const Problem p = make_problem(load_scene("bowl-planar"));
  const auto& exact = dynamic_cast<const BowlPendulumSolution&>(*p.exact());
  // at t = 0 it is the start
  const ExactState e0 = exact.at(0.0);
  EXPECT_LT((e0.alpha - contact_of(p.y0())).norm(), 1e-15);
  EXPECT_LT(e0.omega.norm(), 1e-15);
  EXPECT_LT((e0.R - rotation_of(p.y0())).norm(), 1e-15);
  // energy is constant along it and theta_dot is the derivative of theta
  const double H0 = p.model().derived(flat_of(p, e0)).energy;
  for (double t = 0.0; t < 5.0; t += 0.01) {
    EXPECT_NEAR(p.model().derived(flat_of(p, exact.at(t))).energy, H0, 1e-12 * std::abs(H0)) << "t = " << t;
    const double d = 1e-5;
    EXPECT_NEAR((exact.theta(t + d) - exact.theta(t - d)) / (2 * d), exact.theta_dot(t), 1e-8);
  }
  // after a full period it is back at the start
  EXPECT_LT((exact.at(exact.period()).alpha - e0.alpha).norm(), 1e-12);
}

TEST(ClosedForm, BowlThreeDimensionalKeepsSpinAndEnergy) {
  const Problem p = make_problem(load_scene("bowl-3d"));
  const RunResult r = run(p, "rkmk4", 0.01, 1e-3);
  const Derived d0 = p.model().derived(p.y0());
  EXPECT_NEAR(d0.spin, 0.5, 1e-14);
  double spin_drift = 0.0, energy_drift = 0.0, travelled = 0.0;
  for (const FlatState& y : r.output.y) {
    const Derived d = p.model().derived(y);
    spin_drift = std::max(spin_drift, std::abs(d.spin - d0.spin));
    energy_drift = std::max(energy_drift, std::abs(d.energy - d0.energy));
    travelled = std::max(travelled, std::abs(y[kOffsetAlpha + 1]));
  }
  EXPECT_GT(travelled, 0.3) << "the start is sideways: the ball leaves the vertical plane";
  EXPECT_LT(spin_drift, 1e-10);                          // omega . N constant in a spherical bowl
  EXPECT_LT(energy_drift, 1e-10 * std::abs(d0.energy));  // energy constant
}

TEST(ClosedForm, EnergyIsConstantOnCurvedLandscapes) {
  for (const char* name : {"valley-rest", "valley-sideways", "gaussian-hills", "saddle", "bumpy-long"}) {
    SCOPED_TRACE(name);
    const Problem p = make_problem(load_scene(name));
    const RunResult r = run(p, "rkmk4", 0.05, 1e-3);
    const double H0 = p.model().derived(p.y0()).energy;
    const double scale = std::abs(H0) + 1.0;
    for (const FlatState& y : r.output.y) {
      const Derived d = p.model().derived(y);
      EXPECT_NEAR(d.energy, H0, 1e-10 * scale);
      EXPECT_LT(d.rotation_defect, 1e-13);  // RKMK keeps R in SO(3) to rounding
    }
  }
}

TEST(ClosedForm, ExactSolutionsMatchAFineRkmk4Run) {
  for (const char* name : {"plane", "incline-spin", "bowl-planar"}) {
    SCOPED_TRACE(name);
    const Problem p = make_problem(load_scene(name));
    ASSERT_NE(p.exact(), nullptr);
    const RunResult r = run(p, "rkmk4", 0.05, 1e-3);
    for (std::size_t i = 0; i < r.output.t.size(); ++i) {
      const ExactState e = p.exact()->at(r.output.t[i]);
      const FlatState& y = r.output.y[i];
      // rkmk4 at h = 1e-3 is accurate to ~1e-12 here; 1e-9 leaves room
      EXPECT_LT((contact_of(y) - e.alpha).norm(), 1e-9) << "t = " << r.output.t[i];
      EXPECT_LT((omega_of(p, y) - e.omega).norm(), 1e-9) << "t = " << r.output.t[i];
      if (e.has_rotation) {
        EXPECT_LT(rotation_angle_between(e.R, rotation_of(y)), 1e-9) << "t = " << r.output.t[i];
      }
    }
  }
}

TEST(ClosedForm, ExactNamesAndNone) {
  EXPECT_EQ(exact_names(), (std::vector<std::string>{"bowl-pendulum", "incline", "plane"}));
  const Scene scene = load_scene("valley-rest");
  EXPECT_EQ(make_exact(scene, make_model(scene)), nullptr);
}

}  // namespace
}  // namespace rb

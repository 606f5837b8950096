// The cheap projection of rk4-projected against the SVD's, and dexpinv's
// guard at its pole |u| = 2 pi.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace rb {
namespace {

TEST(Projection, NewtonSchulzGivesTheSvdsRotationToRounding) {
  Mat3 drift;
  drift << 1, 2, -1, 0.5, -1, 2, 1, 1, -0.5;
  for (const Vec3& axis : {Vec3(0.3, -0.2, 0.5), Vec3(2.0, 1.0, -1.5), Vec3(0.0, 0.0, 3.1)})
    for (const double size : {1e-12, 1e-9, 1e-6, 1e-3, 5e-2}) {
      const Mat3 M = so3_exp(axis) + size * drift;
      const Mat3 P = project_to_so3_newton_schulz(M);
      EXPECT_LT(rotation_defect(P), 1e-15) << "off by " << size;
      EXPECT_NEAR(P.determinant(), 1.0, 1e-15);
      // within the SVD's own rounding (a few ulps)
      EXPECT_LT((P - project_to_so3(M)).cwiseAbs().maxCoeff(), 3e-15) << "off by " << size;
    }
}

TEST(Projection, FarFromSo3OrAReflectionGoesToTheSvd) {
  Mat3 far;
  far << 2, 0.5, 0, 0, 0.3, 0.1, 0.2, 0, 1;
  EXPECT_EQ(project_to_so3_newton_schulz(far), project_to_so3(far));
  const Mat3 reflection = Vec3(1, 1, -1).asDiagonal();
  const Mat3 P = project_to_so3_newton_schulz(reflection);
  EXPECT_NEAR(P.determinant(), 1.0, 1e-15);
  EXPECT_EQ(P, project_to_so3(reflection));
}

TEST(Projection, BothBaselinesAreRegisteredAndAgree) {
  const Integrator& cheap = find_integrator("rk4-projected");
  const Integrator& svd = find_integrator("rk4-projected-svd");
  EXPECT_EQ(cheap.family(), "projection");
  EXPECT_EQ(svd.family(), "projection");
  const Problem problem = make_problem(load_scene("bowl-3d"));
  RunOptions o;
  o.h = 0.01;
  o.t_end = 2.0;
  const RunResult a = cheap.integrate(problem, o), b = svd.integrate(problem, o);
  ASSERT_EQ(a.status, Status::ok);
  ASSERT_EQ(b.status, Status::ok);
  EXPECT_LT((a.final_state - b.final_state).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(rotation_defect(rotation_of(a.final_state)), 1e-14);
}

// dexp_u(v) = v + (1 - cos t) / t^2 u x v + (t - sin t) / t^3 u x (u x v)
Vec3 dexp(const Vec3& u, const Vec3& v) {
  const double t = u.norm();
  return v + (1 - std::cos(t)) / (t * t) * u.cross(v) + (t - std::sin(t)) / (t * t * t) * u.cross(u.cross(v));
}

TEST(Dexpinv, InvertsDexpUpToItsLimitAndIsNanFromThere) {
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  const Vec3 w(0.3, 0.7, -1.1);
  for (const double t : {0.5, 2.0, M_PI, 5.0, kDexpinvMaxAngle * (1 - 1e-9)}) {
    const Vec3 back = dexp(t * axis, dexpinv(t * axis, w));
    EXPECT_LT((back - w).norm(), 1e-13) << "|u| = " << t;
  }
  for (const double t : {kDexpinvMaxAngle, 2 * M_PI, 2 * M_PI * (1 + 1e-12), 9.0})
    EXPECT_TRUE(dexpinv(t * axis, w).array().isNaN().all()) << "|u| = " << t;
  // the truncated forms have no pole
  EXPECT_TRUE(dexpinv(2 * M_PI * axis, w, DexpinvKind::truncated).allFinite());
}

// A step whose rotation reaches the pole ends a fixed-step run at the last
// valid state with the status chart-limit (not diverged: the state is
// finite, the step left the chart); an adaptive run rejects it and goes on.
TEST(Dexpinv, AStepAtThePoleIsAStatusNeverAValue) {
  const Problem problem = make_problem(load_scene("bowl-3d"));
  const double spin = problem.model().derived(problem.y0()).omega.norm();
  RunOptions o;
  o.h = 1.02 * kDexpinvMaxAngle / spin;  // the first step's rotation passes the limit
  o.t_end = 4 * o.h;
  const RunResult fixed = find_integrator("rkmk4").integrate(problem, o);
  // the state has not diverged: the step left the exponential chart
  EXPECT_EQ(fixed.status, Status::chart_limit);
  EXPECT_EQ(status_name(fixed.status), "chart-limit");
  EXPECT_NE(fixed.message.find("past the exponential chart's edge"), std::string::npos) << fixed.message;
  EXPECT_EQ(fixed.stop_time, 0.0);
  EXPECT_EQ(fixed.final_state, problem.y0());
  RunOptions a;
  a.h = o.h;  // the first step tried
  a.tolerances = Tolerances(1e-6, 1e-6);
  a.t_end = 2.0;
  const RunResult adaptive = find_integrator("rkmk-dp54-adaptive").integrate(problem, a);
  EXPECT_EQ(adaptive.status, Status::ok);
  EXPECT_GT(adaptive.cost.rejected, 0);
}

// The same stop on each fixed-step code path: the homogeneous ball's and an
// anisotropic ball's (General), with the stages unrolled (rkmk4) or looped
// (rkmk5); each tests a stage's U against the edge before its dexpinv.
TEST(Dexpinv, AFixedStepAtThePoleStopsOnEveryCodePath) {
  for (const char* scene : {"bowl-3d", "chaplygin-valley"})
    for (const char* method : {"rkmk4", "rkmk5"}) {
      const Problem problem = make_problem(load_scene(scene));
      const double spin = problem.model().derived(problem.y0()).omega.norm();
      RunOptions o;
      o.h = 1.02 * kDexpinvMaxAngle / spin;
      o.t_end = 4 * o.h;
      const RunResult fixed = find_integrator(method).integrate(problem, o);
      EXPECT_EQ(fixed.status, Status::chart_limit) << scene << " " << method << ": " << fixed.message;
      EXPECT_NE(fixed.message.find("past the exponential chart's edge"), std::string::npos) << fixed.message;
      EXPECT_EQ(fixed.final_state, problem.y0()) << scene << " " << method;
    }
}

// A step whose stage passes the edge stops there: the stages after it, which
// a large step may take beyond the model's limits (bowl-planar at h = 1: off
// the landscape's finite region), are not looked at, so the stop is the
// chart's, not theirs (the default preset's runs of rkmk4 and rkmk5 there).
TEST(Dexpinv, AStageAtThePoleStopsItsStepBeforeLaterStagesAreSeen) {
  const Problem problem = make_problem(load_scene("bowl-planar"));
  RunOptions o;
  o.h = 1.0;
  o.t_end = 4.0;
  for (const char* method : {"rkmk4", "rkmk5"}) {
    const RunResult fixed = find_integrator(method).integrate(problem, o);
    EXPECT_EQ(fixed.status, Status::chart_limit) << method << ": " << fixed.message;
    EXPECT_NE(fixed.message.find("past the exponential chart's edge"), std::string::npos) << fixed.message;
    EXPECT_EQ(fixed.stop_time, 0.0) << method;
  }
}

}  // namespace
}  // namespace rb

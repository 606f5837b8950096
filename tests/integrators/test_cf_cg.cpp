// The methods made of exponentials only (commutator-free, Crouch-Grossman)
// and RKMK with the Cayley map: the maps against closed forms and finite
// differences, R on SO(3), the observed orders where R feeds back and where
// it does not, the exponentials counted, and the anisotropic code path
// against the homogeneous one.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/exp_product/cf4.hpp"
#include "integrators/families/exp_product/cg3.hpp"
#include "integrators/families/exp_product/exp_product.hpp"
#include "integrators/registry.hpp"
#include "problems/cayley.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using testing::every;
using testing::fixed;
using testing::valley;

const std::vector<Vec3>& sample_vectors() {
  static const std::vector<Vec3> v = {Vec3(0.3, -0.2, 0.5), Vec3(1e-5, 2e-5, -3e-5), Vec3(2.0, 1.0, -2.5),
                                      Vec3(0.0, 0.0, 7.0)};
  return v;
}

TEST(Cayley, ClosedFormIsTheRationalMapAndARotation) {
  for (const Vec3& u : sample_vectors()) {
    const Mat3 U = hat(u);
    const Mat3 rational = (Mat3::Identity() - 0.5 * U).inverse() * (Mat3::Identity() + 0.5 * U);
    const Mat3 C = so3_cay(u);
    EXPECT_LT((C - rational).norm(), 1e-14 * (1.0 + u.squaredNorm())) << u.transpose();
    EXPECT_LT(rotation_defect(C), 1e-15) << u.transpose();
    EXPECT_NEAR(C.determinant(), 1.0, 1e-15);
  }
}

TEST(Cayley, AgreesWithExpToThirdOrder) {
  // cay(u) - exp(u) = O(|u|^3): the ratio at u and u / 2 is about 8
  const Vec3 u(0.02, -0.01, 0.015);
  const double e1 = (so3_cay(u) - so3_exp(u)).norm();
  const double e2 = (so3_cay(0.5 * u) - so3_exp(0.5 * u)).norm();
  EXPECT_NEAR(e1 / e2, 8.0, 0.1);
}

TEST(Cayley, DcayinvInvertsTheDerivativeByFiniteDifferences) {
  // d/de cay(u + e d) at e = 0, times cay(u)^T, is hat(w) for d = dcayinv_u(w)
  const Vec3 w(0.7, -1.1, 0.4);
  for (const Vec3& u : sample_vectors()) {
    const Vec3 d = dcayinv(u, w);
    const double e = 1e-6;
    const Mat3 derivative = (so3_cay(u + e * d) - so3_cay(u - e * d)) / (2 * e);
    const Mat3 W = derivative * so3_cay(u).transpose();
    EXPECT_LT((W - hat(w)).norm(), 1e-8 * (1.0 + d.norm())) << "u = " << u.transpose();
  }
}

const Problem& chaplygin_valley() {
  static const Problem problem = make_problem(load_scene("chaplygin-valley"));
  return problem;
}

const std::vector<std::string>& new_methods() {
  static const std::vector<std::string> names = {"cf4",          "cg3",          "cg4a",         "rkmk4-cayley",
                                                 "cf4-reversed", "cg3-reversed", "cg4a-reversed"};
  return names;
}

TEST(CfCg, RotationStaysOnSO3OverTenThousandSteps) {
  for (const Problem* p : {&valley(), &chaplygin_valley()})
    for (const std::string& name : new_methods()) {
      const RunResult run = find_integrator(name).integrate(*p, every(0.1, 2.0, 2e-4));
      ASSERT_EQ(run.status, Status::ok) << name << " on " << p->name() << ": " << run.message;
      EXPECT_EQ(run.cost.steps, 10000) << name;
      double worst = 0.0;
      for (const FlatState& y : run.output.y) worst = std::max(worst, rotation_defect(rotation_of(y)));
      EXPECT_LT(worst, 1e-13) << name << " on " << p->name();
    }
}

// rkmk4 at h = 5e-5: far below every error fitted (test_registry_order.cpp)
FlatState reference_of(const Problem& problem) {
  return find_integrator("rkmk4").integrate(problem, fixed(5e-5, 1.0)).final_state;
}

testing::Convergence convergence_of(const std::string& name, const Problem& problem) {
  static const FlatState homogeneous = reference_of(valley());
  static const FlatState anisotropic = reference_of(chaplygin_valley());
  const FlatState& ref = &problem == &valley() ? homogeneous : anisotropic;
  const testing::Convergence c = testing::measure_convergence(find_integrator(name), problem, 1.0, ref);
  std::printf("  %-14s %-17s order: contact %.2f, omega %.2f, rotation %.2f (%d points)\n", name.c_str(),
              problem.name().c_str(), c.contact_fit.slope, c.omega_fit.slope, c.rotation_fit.slope,
              c.contact_fit.points);
  return c;
}

TEST(CfCg, DeclaredOrderInEveryComponentWithAndWithoutFeedback) {
  for (const Problem* p : {&valley(), &chaplygin_valley()})
    for (const char* name : {"cf4", "cg3", "cg4a", "rkmk4-cayley"}) {
      const testing::Convergence c = convergence_of(name, *p);
      const int order = find_integrator(name).declared_order();
      SCOPED_TRACE(std::string(name) + " on " + p->name());
      ASSERT_GE(c.contact_fit.points, 3);
      EXPECT_NEAR(c.contact_fit.slope, order, 0.2) << "contact";
      EXPECT_NEAR(c.omega_fit.slope, order, 0.2) << "omega";
      EXPECT_NEAR(c.rotation_fit.slope, order, 0.2) << "rotation";
    }
}

// Composed the other way round, the update's h^3 commutator term has the
// wrong sign (integrators/families/exp_product/cg3.hpp): order 2 in R, and where R feeds back in
// every component. Printed for docs/integrators.md; the prediction asserted.
TEST(CfCg, ReversedCompositionLosesOrder) {
  for (const char* name : {"cf4-reversed", "cg3-reversed", "cg4a-reversed"}) {
    const testing::Convergence flat = convergence_of(name, valley());
    EXPECT_NEAR(flat.rotation_fit.slope, 2.0, 0.2) << name;
    EXPECT_NEAR(flat.contact_fit.slope, find_integrator(name).declared_order(), 0.2) << name;
    const testing::Convergence fed = convergence_of(name, chaplygin_valley());
    EXPECT_NEAR(fed.rotation_fit.slope, 2.0, 0.2) << name;
    EXPECT_NEAR(fed.contact_fit.slope, 2.0, 0.2) << name;
  }
}

struct ExpCount {
  const char* name;
  long stages;
  long homogeneous, anisotropic;  // so(3) exponentials (or cayley maps) a step
};

TEST(CfCg, ExponentialsCountedPerStep) {
  const ExpCount expected[] = {{"cf4", 4, 2, 5},          {"cg3", 3, 3, 6},          {"cg4a", 5, 5, 15},
                               {"cf4-reversed", 4, 2, 6}, {"cg3-reversed", 3, 3, 6}, {"cg4a-reversed", 5, 5, 15},
                               {"rkmk4-cayley", 4, 1, 4}};
  for (const ExpCount& e : expected) {
    const Integrator& m = find_integrator(e.name);
    for (const Problem* p : {&valley(), &chaplygin_valley()}) {
      const RunResult run = m.integrate(*p, fixed(0.01, 1.0));
      ASSERT_EQ(run.status, Status::ok);
      const long per_step = p == &valley() ? e.homogeneous : e.anisotropic;
      EXPECT_EQ(run.cost.exp_evals, per_step * run.cost.steps) << e.name << " on " << p->name();
      EXPECT_EQ(run.cost.rhs_evals, e.stages * run.cost.steps) << e.name;
      EXPECT_EQ(run.cost.dexpinv_evals, m.name() == "rkmk4-cayley" ? 3 * run.cost.steps : 0) << e.name;
    }
    // the description states the counts exponentials_per_step finds
    if (m.family() == "cf" || m.family() == "cg") {
      EXPECT_NE(m.description().find(std::to_string(e.anisotropic) + " exponentials a step (" +
                                     std::to_string(e.homogeneous) + " for a homogeneous ball)"),
                std::string::npos)
          << e.name << ": " << m.description();
    }
  }
}

// A ball with inertia theta = (2/5) m r^2 in every direction is the
// homogeneous one. Equal moments take the general code with R at each
// stage unused; moments unequal in the last digit take the anisotropic
// path, with the stage orientations, and must still land on it to rounding.
TEST(CfCg, AnisotropicPathWithHomogeneousInertiaMatchesTheHomogeneousBall) {
  const Scene base = load_scene("valley-sideways");
  const double theta = 0.4 * base.ball.mass * base.ball.radius * base.ball.radius;
  Scene equal = base, nearly = base;
  equal.ball.inertia = Vec3(theta, theta, theta);
  nearly.ball.inertia = Vec3(theta, theta, theta * (1.0 + 4e-16));
  const Problem p_equal = make_problem(equal), p_nearly = make_problem(nearly);
  ASSERT_FALSE(p_equal.model().anisotropic());
  ASSERT_TRUE(p_nearly.model().anisotropic());
  for (const std::string& name : new_methods()) {
    const RunOptions o = every(0.1, 2.0, 0.01);
    const RunResult a = find_integrator(name).integrate(valley(), o);
    for (const Problem* p : {&p_equal, &p_nearly}) {
      const RunResult b = find_integrator(name).integrate(*p, o);
      ASSERT_EQ(b.status, Status::ok);
      ASSERT_EQ(a.output.y.size(), b.output.y.size());
      for (std::size_t i = 0; i < a.output.y.size(); ++i)
        EXPECT_LT((a.output.y[i] - b.output.y[i]).lpNorm<Eigen::Infinity>(), 1e-12)
            << name << " at t = " << a.output.t[i] << (p == &p_nearly ? " (anisotropic path)" : "");
    }
  }
}

TEST(CfCg, MalformedSchemeIsRefused) {
  ExpProductScheme s = methods::cg3();
  s.stages[1] = {{0.5, 0.5}};  // stage 2 cannot use F_2
  try {
    (void)exp_product_method(s, "cg3", kConstantController);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "cg3 stage 2 uses a field not yet computed");
  }
}

TEST(CfCg, ReversedComposesEveryProductTheOtherWay) {
  const ExpProductScheme s = methods::cf4();
  const ExpProductScheme r = reversed(s);
  EXPECT_EQ(r.name, "cf4-reversed");
  EXPECT_EQ(exponentials_per_step(r, true), 6);
  EXPECT_EQ(exponentials_per_step(s, true), 5);
  EXPECT_EQ(r.update.front(), s.update.back());
  EXPECT_EQ(r.stages[3].front(), s.stages[3].back());
  EXPECT_EQ(r.stages[1], s.stages[1]);
  // declared as the paper's method, with the order in R it loses
  const Integrator& registered = find_integrator("cg4a-reversed");
  EXPECT_EQ(registered.declared_order(), 4);
  EXPECT_EQ(registered.rotation_order(), 2);
  EXPECT_EQ(find_integrator("cg4a").rotation_order(), 4);
}

}  // namespace
}  // namespace rb

// The high-order tableaus and the adaptive Runge-Kutta-Munthe-Kaas methods:
// every order condition (all rooted trees) of the pairs and their dense
// outputs, R on SO(3) on every shipped scene, the dense output against
// stepping to the same time, the cost counts, and an error estimate that
// does not look at R. Registry-wide tests (order, tolerance, statuses) cover
// the rest.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "integrators/families/rkmk/munthe_kaas.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/order_conditions.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

// ---- order conditions on rooted trees ----

// The highest order (at most max_order) whose conditions all hold to 1e-12,
// for weights w (theta != 1: a continuous extension at theta); c = A 1.
int satisfied(const std::vector<double>& a, const std::vector<double>& w, int s, int max_order, double theta = 1.0) {
  std::vector<double> c(static_cast<std::size_t>(s), 0.0);
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < s; ++j) c[static_cast<std::size_t>(i)] += a[static_cast<std::size_t>(i * s + j)];
  return check_order_conditions(s, a, w, c, max_order, theta).satisfied_order;
}

std::vector<double> minus(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> d(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) d[i] = x[i] - y[i];
  return d;
}

std::vector<Tableau> all_pairs() {
  return {methods::bogacki_shampine32(), methods::dormand_prince54(), methods::dormand_prince853(),
          methods::fehlberg78()};
}

std::vector<double> b_of(const Tableau& t) {
  std::vector<double> b;
  for (int j = 0; j < t.total_stages(); ++j) b.push_back(t.b(j));
  return b;
}

TEST(LieAdaptive, PairsSatisfyEveryOrderConditionOfTheirOrdersAndNoMore) {
  // propagating b, embedded b - e (DP853: b - e is its 5th-order, b - e_stretched its 3rd-order member)
  struct Want {
    int b, embedded, embedded3;
  };
  const Want want[] = {{3, 2, 0}, {5, 4, 0}, {8, 5, 3}, {8, 7, 0}};
  const std::vector<Tableau> ps = all_pairs();
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const Tableau& p = ps[k];
    SCOPED_TRACE(p.name());
    const int s = p.total_stages();
    EXPECT_EQ(satisfied(p.a_row_major(), b_of(p), s, 8), want[k].b);
    EXPECT_EQ(p.order(), want[k].b);
    EXPECT_EQ(satisfied(p.a_row_major(), minus(b_of(p), p.e()), s, 8), want[k].embedded);
    EXPECT_EQ(p.embedded_order(), want[k].embedded);
    if (!p.e_stretched().empty()) {
      EXPECT_EQ(satisfied(p.a_row_major(), minus(b_of(p), p.e_stretched()), s, 8), want[k].embedded3);
      EXPECT_EQ(p.stretched_order(), want[k].embedded3);
    }
    // b weights the attempt's stages only; the FSAL row is b
    for (int j = p.stages(); j < s; ++j) EXPECT_EQ(p.b(j), 0.0);
    if (p.fsal_stage()) {
      const int f = *p.fsal_stage();
      EXPECT_EQ(p.c(f), 1.0);
      for (int j = 0; j < s; ++j) EXPECT_EQ(p.a(f, j), p.b(j));
    }
  }
}

TEST(LieAdaptive, FixedStepTableausPassQuadratureConditionsToTheirOrder) {
  // what rkmk5 and rkmk8 step with: the propagating weights of dp54 and f78
  for (const Tableau& t : {methods::dormand_prince54(), methods::fehlberg78()}) {
    SCOPED_TRACE(t.name());
    EXPECT_EQ(t.satisfied_order(), t.order());
    // sum b_i c_i^(k-1) = 1/k and sum b_i c_i^(k-2) (A c)_i = 1/(k (k-1) ... ) via all trees
    for (int k = 1; k <= t.order(); ++k) {
      double sum = 0.0;
      for (int i = 0; i < t.stages(); ++i) sum += t.b(i) * std::pow(t.c(i), k - 1);
      EXPECT_NEAR(sum, 1.0 / k, 1e-13) << "k = " << k;
    }
    std::vector<double> a(static_cast<std::size_t>(t.stages() * t.stages())), b(static_cast<std::size_t>(t.stages()));
    for (int i = 0; i < t.stages(); ++i) {
      b[static_cast<std::size_t>(i)] = t.b(i);
      for (int j = 0; j < t.stages(); ++j) a[static_cast<std::size_t>(i * t.stages() + j)] = t.a(i, j);
    }
    EXPECT_EQ(satisfied(a, b, t.stages(), 8), t.order());
  }
}

TEST(LieAdaptive, DenseOutputsAreContinuousExtensionsOfTheirOrder) {
  for (const Tableau& p : all_pairs()) {
    if (p.dense_order() == 0) continue;
    SCOPED_TRACE(p.name());
    const int s = p.total_stages(), degree = p.dense_degree();
    for (const double theta : {0.13, 0.5, 0.77, 1.0}) {
      std::vector<double> w(static_cast<std::size_t>(s));
      for (int j = 0; j < s; ++j) {
        double bj = 0.0;
        for (int q = 0; q < degree; ++q)
          bj += p.dense()[static_cast<std::size_t>(j * degree + q)] * std::pow(theta, q + 1);
        w[static_cast<std::size_t>(j)] = bj;
        if (theta == 1.0) {
          EXPECT_NEAR(bj, p.b(j), 1e-12) << "b_" << j << "(1)";
        }
      }
      EXPECT_GE(satisfied(p.a_row_major(), w, s, 8, theta), p.dense_order()) << "theta " << theta;
    }
  }
}

TEST(LieAdaptive, RefusesTableauxWithoutAnErrorEstimate) {
  try {
    (void)rkmk_integrator(Tableau("rk2", 2, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1}), "x", "pi");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "'e': tableau 'rk2' has no embedded weights for an adaptive method");
  }
}

// ---- runs ----

using testing::shipped_scene;
using testing::tolerance_every;

const char* const kAdaptive[] = {"rkmk-bs32-adaptive", "rkmk-dp54-adaptive", "rkmk-dp853-adaptive",
                                 "rkmk-f78-adaptive"};

TEST(LieAdaptive, RegisteredAsAdaptiveLieMethods) {
  const int orders[] = {3, 5, 8, 8};
  for (int k = 0; k < 4; ++k) {
    const Integrator& m = find_integrator(kAdaptive[k]);
    EXPECT_EQ(m.family(), "rkmk-adaptive");
    EXPECT_TRUE(m.adaptive());
    EXPECT_EQ(m.declared_order(), orders[k]);
  }
  EXPECT_EQ(find_integrator("rkmk5").declared_order(), 5);
  EXPECT_EQ(find_integrator("rkmk8").declared_order(), 8);
}

TEST(LieAdaptive, RotationStaysOnSO3OnEveryShippedScene) {
  for (const std::string& name : shipped_scene_names()) {
    const Problem& p = shipped_scene(name);
    for (const char* method :
         {"rkmk-bs32-adaptive", "rkmk-dp54-adaptive", "rkmk-dp853-adaptive", "rkmk-f78-adaptive", "rkmk5", "rkmk8"}) {
      const Integrator& m = find_integrator(method);
      RunOptions o = tolerance_every(1e-8, 0.1, p.t_end());
      o.h = m.adaptive() ? 0.0 : 0.01;
      if (!m.adaptive()) o.tolerances = {};
      const RunResult r = m.integrate(p, o);
      EXPECT_EQ(r.status, Status::ok) << name << " " << method << ": " << r.message;
      ASSERT_FALSE(r.output.y.empty());
      double worst = 0.0;
      for (const FlatState& y : r.output.y) worst = std::max(worst, rotation_defect(rotation_of(y)));
      EXPECT_LE(worst, 1e-13) << name << " " << method;
    }
  }
}

// The dense output at t against a run whose steps land on t: within 10
// tolerances of each other, and within the registry's 100 of a fine reference
// (BS32's global error in R reaches 10 tolerances by t = 1).
TEST(LieAdaptive, DenseOutputAgreesWithSteppingToTheSameTime) {
  const Problem& p = shipped_scene("valley-sideways");
  for (const char* method : {"rkmk-bs32-adaptive", "rkmk-dp54-adaptive", "rkmk-dp853-adaptive"}) {
    const Integrator& m = find_integrator(method);
    SCOPED_TRACE(method);
    for (const double tol : {1e-6, 1e-9}) {
      const RunResult dense = m.integrate(p, tolerance_every(tol, 0.1, 1.0));
      ASSERT_EQ(dense.status, Status::ok);
      ASSERT_EQ(dense.output.t.size(), 10u);
      for (std::size_t k = 0; k + 1 < dense.output.t.size(); ++k) {
        const double t = dense.output.t[k];
        RunOptions o = tolerance_every(tol, 1.0, t);
        const RunResult stepped = m.integrate(p, o);
        ASSERT_EQ(stepped.status, Status::ok);
        RunOptions fine;
        fine.t_end = t;
        fine.h = 1e-4;
        const FlatState ref = find_integrator("rkmk4").integrate(p, fine).final_state;
        const testing::EndErrors d = testing::end_errors(p, dense.output.y[k], stepped.final_state);
        const testing::EndErrors e = testing::end_errors(p, dense.output.y[k], ref);
        EXPECT_LE(d.contact, 10 * tol) << "t = " << t;
        EXPECT_LE(d.rotation, 10 * tol) << "t = " << t;
        EXPECT_LE(e.contact, 100 * tol) << "t = " << t;
        EXPECT_LE(e.rotation, 100 * tol) << "t = " << t;
        EXPECT_LE(rotation_defect(rotation_of(dense.output.y[k])), 1e-14);
      }
    }
  }
}

// Clamped steps (no dense output) record the same outputs to the tolerance.
TEST(LieAdaptive, DenseAndClampedOutputsAgree) {
  const Problem& p = shipped_scene("bowl-3d");
  const auto dense = rkmk_integrator(methods::dormand_prince853(), "dense", "pi");
  const auto clamped = rkmk_integrator(methods::dormand_prince853(), "clamped", "pi", DexpinvKind::exact, false);
  const RunOptions o = tolerance_every(1e-9, 0.05, 2.0);
  const RunResult a = dense->integrate(p, o), b = clamped->integrate(p, o);
  ASSERT_EQ(a.status, Status::ok);
  ASSERT_EQ(b.status, Status::ok);
  ASSERT_EQ(a.output.t, b.output.t);
  EXPECT_LT(a.cost.steps, b.cost.steps);  // outputs no longer cut steps
  for (std::size_t k = 0; k < a.output.y.size(); ++k) {
    const testing::EndErrors d = testing::end_errors(p, a.output.y[k], b.output.y[k]);
    EXPECT_LE(d.contact, 1e-8) << a.output.t[k];
    EXPECT_LE(d.rotation, 1e-8) << a.output.t[k];
  }
}

// Per attempt: stages - 1 rhs and dexpinv; per accepted step one exp (and one
// rhs for the next first stage where it is not an attempt's stage); per
// interpolated output one exp; 2 rhs for the initial step and 1 at the start.
TEST(LieAdaptive, CountsRhsExpAndDexpinv) {
  const Problem& p = shipped_scene("gaussian-hills");
  const std::vector<Tableau> tableaux = all_pairs();  // in kAdaptive's order
  for (std::size_t k = 0; k < tableaux.size(); ++k) {
    const char* method = kAdaptive[k];
    const Integrator& m = find_integrator(method);
    const Tableau& pair = tableaux[k];
    SCOPED_TRACE(method);
    RunOptions o = tolerance_every(1e-8, 1.0, 1.0);  // t_end only: no interpolation
    const RunResult r = m.integrate(p, o);
    ASSERT_EQ(r.status, Status::ok);
    const long attempts = r.cost.steps + r.cost.rejected;
    const int stages = pair.attempt_stages();
    const bool fsal_in_attempt = pair.fsal_stage() && *pair.fsal_stage() < stages;
    const long after_accept = fsal_in_attempt ? 0 : r.cost.steps;
    EXPECT_EQ(r.cost.dexpinv_evals, (stages - 1) * attempts);
    EXPECT_EQ(r.cost.rhs_evals, 2 + 1 + (stages - 1) * attempts + after_accept);
    EXPECT_EQ(r.cost.exp_evals, r.cost.steps);
    EXPECT_EQ(r.cost.jacobian_evals, 0);
    if (pair.dense_order() > 0) {
      const RunResult with_outputs = m.integrate(p, tolerance_every(1e-8, 0.01, 1.0));
      ASSERT_EQ(with_outputs.status, Status::ok);
      // 99 outputs inside steps, t_end at a step's end
      EXPECT_EQ(with_outputs.cost.exp_evals, with_outputs.cost.steps + 99);
    }
  }
}

// The estimate is on (u, z): starting from another orientation (R(0) R0, so
// R(t) R0 is the solution) gives the same steps and the same z, bit for bit.
// The first step is given: initial_step guesses it on the flat view.
TEST(LieAdaptive, ErrorEstimateDoesNotSeeR) {
  const Problem& p = shipped_scene("valley-sideways");
  FlatState y0 = p.y0();
  const Mat3 R0 = so3_exp(Vec3(0.3, -1.1, 2.0));
  set_rotation(y0, rotation_of(p.y0()) * R0);
  const Problem turned(p.name(), p.model(), y0, p.t_end(), p.domain());
  for (const char* method : kAdaptive) {
    const Integrator& m = find_integrator(method);
    RunOptions o = tolerance_every(1e-7, 0.5, 2.0);
    o.h = 0.01;
    const RunResult a = m.integrate(p, o), b = m.integrate(turned, o);
    ASSERT_EQ(a.status, Status::ok);
    ASSERT_EQ(b.status, Status::ok);
    EXPECT_EQ(a.cost.steps, b.cost.steps) << method;
    EXPECT_EQ(a.cost.rejected, b.cost.rejected) << method;
    EXPECT_EQ(z_of(a.final_state), z_of(b.final_state)) << method;
    EXPECT_LT((rotation_of(a.final_state) * R0 - rotation_of(b.final_state)).norm(), 1e-13) << method;
  }
}

// The stop reasons of docs/model.md end an adaptive run as they end rkmk4's.
TEST(LieAdaptive, StopsWithTheModelsStatuses) {
  const std::pair<const char*, Status> cases[] = {{"stop-lift-off.json", Status::lift_off},
                                                  {"stop-curvature.json", Status::curvature},
                                                  {"stop-domain.json", Status::domain},
                                                  {"stop-nonfinite.json", Status::diverged}};
  for (const auto& [file, want] : cases) {
    const Problem p = make_problem(load_scene(std::string(RB_TEST_DATA) + "/" + file));
    for (const char* method : kAdaptive) {
      const RunResult r = find_integrator(method).integrate(p, tolerance_every(1e-8, 0.01, p.t_end()));
      EXPECT_EQ(status_name(r.status), status_name(want)) << file << " " << method << ": " << r.message;
      EXPECT_LT(r.stop_time, p.t_end());
      EXPECT_TRUE(r.final_state.allFinite());
      ASSERT_FALSE(r.output.t.empty());
      EXPECT_LE(r.output.t.back(), r.stop_time);
    }
  }
}

}  // namespace
}  // namespace rb

// Time reversal (docs/model.md, "Time reversal"): the exact flow is
// reversible under rho(R, v, alpha) = (R, -v, alpha) for the homogeneous and
// the anisotropic ball; symmetric methods keep that to their solver's
// tolerance, explicit ones miss it by O(h^p).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bench/lib/reversibility.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb {
namespace {

RunOptions fixed(double h, double t_end) {
  RunOptions o;
  o.h = h;
  o.t_end = t_end;
  return o;
}

RunOptions tolerance(double tol, double t_end) {
  RunOptions o;
  o.tolerances = Tolerances(tol, tol);
  o.t_end = t_end;
  return o;
}

Problem shipped(const std::string& name) { return make_problem(read_shipped_scene(name)); }

TEST(Reversibility, TheExactFlowComesBackUnderVToMinusV) {
  // a 9th-order pair at 1e-13 stands for the exact flow; both ball kinds
  for (const char* scene : {"valley-sideways", "chaplygin-valley", "bowl-3d"}) {
    SCOPED_TRACE(scene);
    const ReversibilityDefect d =
        reversibility_defect(find_integrator("rkmk-verner9-adaptive"), shipped(scene), tolerance(1e-13, 1.0));
    ASSERT_EQ(d.status, Status::ok) << d.message;
    EXPECT_LT(d.worst(), 1e-9);
  }
}

TEST(Reversibility, AnotherInvolutionDoesNotComeBack) {
  // the test can fail: reversing the contact point's coordinates as well is no symmetry
  const Problem p = shipped("chaplygin-valley");
  RunOptions o = tolerance(1e-13, 1.0);
  const RunResult forward = find_integrator("rkmk-verner9-adaptive").integrate(p, o);
  FlatState wrong = time_reversed(forward.final_state);
  wrong.segment<3>(kOffsetV) = forward.final_state.segment<3>(kOffsetV);  // v kept: just run on
  const Problem on(p.name(), p.model(), wrong, p.t_end(), p.domain());
  const RunResult back = find_integrator("rkmk-verner9-adaptive").integrate(on, o);
  ASSERT_EQ(back.status, Status::ok) << back.message;
  EXPECT_GT((contact_of(back.final_state) - contact_of(p.y0())).norm() / p.model().params().radius, 1e-2);
}

TEST(Reversibility, ExplicitMethodsMissByTheirOrder) {
  // rk4 and rkmk4, order 4: a local error C h^5 changes sign with h, so the
  // backward leg undoes the forward one's leading error and the defect falls
  // like h^5 (not h^4) per halving of h, far above rounding
  for (const char* method : {"rk4", "rkmk4"}) {
    SCOPED_TRACE(method);
    const Problem p = shipped("chaplygin-valley");
    const ReversibilityDefect coarse = reversibility_defect(find_integrator(method), p, fixed(0.04, 1.0));
    const ReversibilityDefect fine = reversibility_defect(find_integrator(method), p, fixed(0.02, 1.0));
    ASSERT_EQ(coarse.status, Status::ok) << coarse.message;
    ASSERT_EQ(fine.status, Status::ok) << fine.message;
    EXPECT_GT(fine.worst(), 1e-10);
    EXPECT_NEAR(std::log2(coarse.worst() / fine.worst()), 5.0, 0.3);
  }
}

TEST(Reversibility, TheGaussMethodsAreSymmetric) {
  // GSL's implicit Gauss methods (order 2 and 4) are symmetric: their defect is
  // their implicit solve's tolerance, not their order: six orders of magnitude
  // below rk4's at h = 0.01 (2e-6), where gsl-rk2imp's own error is far larger
  const Problem p = shipped("chaplygin-valley");
  const double rk4 = reversibility_defect(find_integrator("rk4"), p, fixed(0.01, 1.0)).worst();
  for (const char* method : {"gsl-rk2imp", "gsl-rk4imp"}) {
    SCOPED_TRACE(method);
    const ReversibilityDefect d = reversibility_defect(find_integrator(method), p, fixed(0.01, 1.0));
    ASSERT_EQ(d.status, Status::ok) << d.message;
    EXPECT_LT(d.worst(), 1e-10);
    EXPECT_LT(d.worst(), 1e-4 * rk4);
  }
}

}  // namespace
}  // namespace rb

namespace rb {
namespace {

TEST(ReversibilityCli, PrintsEachMethodsDefectAndRefusesMissingSettings) {
  const robustness::CliOutcome ok = robustness::rollbench(
      "reversibility chaplygin-valley --integrators rk4,rkmk-verner9-adaptive --h 0.04 --tol "
      "1e-12 --t-end 1");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("reversibility defect on chaplygin-valley over [0, 1] and back"), std::string::npos);
  EXPECT_NE(ok.out.find("  rk4                                  25 "), std::string::npos) << ok.out;
  const auto fail = [](const std::string& args) { return robustness::rollbench("reversibility " + args); };
  EXPECT_EQ(fail("plane --integrators rk4").err, "rollbench: 'h': 'rk4' is a fixed-step method: give --h\n");
  EXPECT_EQ(fail("plane --integrators rkmk-dp54-adaptive --h 0.1").err,
            "rollbench: 'tol': 'rkmk-dp54-adaptive' is adaptive: give --tol\n");
  EXPECT_EQ(fail("plane --integrators rk4 --h -1").code, 2);
  EXPECT_EQ(fail("plane --integrators rk4 --h -1").err, "rollbench: 'h': the step must be a finite number > 0\n");
}

}  // namespace
}  // namespace rb

namespace rb {
namespace {

// A sweep records every fixed-step run's defect beside its error, and the
// Newton of the suite's implicit methods; adaptive runs and explicit
// methods have neither (docs/formats.md, "A run").
TEST(ReversibilityCli, ASweepRecordsEachFixedStepRunsDefectAndTheNewton) {
  const std::string out = robustness::temp_path("reversibility-sweep.json").string();
  const robustness::CliOutcome ran = robustness::rollbench(
      "run --scenes valley-sideways --integrators gauss2,lie-gauss2-tj4,rk4,rkmk-dp54-adaptive --h 2^-4..2^-5 "
      "--tol 1e-6 --repeats 1 --jobs 1 --no-stability --no-horizon --no-finer-steps --out " +
      out);
  ASSERT_EQ(ran.code, 0) << ran.err;
  const nlohmann::json report = nlohmann::json::parse(robustness::slurp(out));
  int fixed = 0;
  for (const nlohmann::json& run : report["runs"]) {
    const std::string name = run["integrator"];
    SCOPED_TRACE(name + " at h = " + run["h"].dump());
    ASSERT_EQ(run["status"], "ok");
    if (name == "rkmk-dp54-adaptive") {
      EXPECT_TRUE(run["reversibility"].is_null());
      EXPECT_TRUE(run["newton"].is_null());
      continue;
    }
    ++fixed;
    const nlohmann::json& d = run["reversibility"];
    ASSERT_EQ(d["status"], "ok");
    EXPECT_EQ(d["worst"].get<double>(),
              std::max({d["contact"].get<double>(), d["rotation"].get<double>(), d["momentum"].get<double>()}));
    if (name == "rk4") {
      EXPECT_GT(d["worst"].get<double>(), 1e-8);
      EXPECT_TRUE(run["newton"].is_null());
      EXPECT_EQ(run["jacobian_evals"], 0);
    } else {
      EXPECT_LT(d["worst"].get<double>(), 1e-12);
      EXPECT_EQ(run["newton"]["tol"], 1e-14);
      EXPECT_EQ(run["newton"]["failures"], 0);
      // one Jacobian a solve, at least two iterations a solve
      const long solves = run["jacobian_evals"].get<long>();
      EXPECT_EQ(solves, run["steps"].get<long>() * (name == "gauss2" ? 1 : 3));
      EXPECT_GE(run["newton"]["iterations"].get<long>(), 2 * solves);
    }
  }
  EXPECT_EQ(fixed, 6);
  std::remove(out.c_str());
}

}  // namespace
}  // namespace rb

// First integrals beyond the energy (docs/model.md, "Invariants beyond the
// energy"): Routh's integrals of a homogeneous ball in a paraboloid and in a
// spherical bowl, the Chaplygin ball's on a plane, each constant to near
// rounding along a run accurate to rounding, and not constant where the
// landscape or the ball breaks their symmetry; the closed forms solve
// Routh's linear ODE; a scene that claims an integral its landscape or ball
// does not have is refused, naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bench/lib/drift.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/invariants.hpp"
#include "problems/scene.hpp"

namespace rb {
namespace {

// A 9th-order pair at 1e-13 stands for the exact flow, recorded every dt.
RunResult accurate_run(const Problem& p, double dt = 0.05) {
  RunOptions o;
  o.tolerances = Tolerances(1e-13, 1e-13);
  o.t_end = p.t_end();
  for (double t = dt; t < p.t_end() - 1e-9; t += dt) o.output_times.push_back(t);
  const RunResult r = find_integrator("rkmk-verner9-adaptive").integrate(p, o);
  EXPECT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.output.y.size(), o.output_times.size() + 1);  // every output recorded, and the end
  return r;
}

// The largest relative change of each integral of one family along a run,
// relative to its magnitude at the start.
std::vector<double> largest_change(const FirstIntegrals& family, const Problem& p, const RunResult& run) {
  const std::size_t n = family.quantities().size();
  std::vector<double> v0(n), m0(n), v(n), m(n), out(n, 0.0);
  family.at(p.y0(), v0.data(), m0.data());
  for (const FlatState& y : run.output.y) {
    family.at(y, v.data(), m.data());
    for (std::size_t i = 0; i < n; ++i) out[i] = std::max(out[i], std::abs(v[i] - v0[i]) / m0[i]);
  }
  return out;
}

double relative_energy_change(const Problem& p, const RunResult& run) {
  const Drift d = largest_drift(p, run.output);
  return d.energy / energy_scale(p);
}

TEST(Invariants, HypergeometricSeriesMatchesIndependentValues) {
  // F(l, l + 2; 2l + 1; x) and x F'(x) for l = +-sqrt(2/7), from mpmath at
  // 30 digits (GSL's gsl_sf_hyperg_2F1 is off by half at l < 0, x = 0.8:
  // 19.30 for 28.70, c = 2l + 1 = -0.069 being near a pole)
  struct Value {
    double sign, x, F, xF;
  };
  const Value values[] = {
      {1.0, 0.05, 1.0342567503589943, 0.035849917075519114}, {1.0, 0.2, 1.1595013135826631, 0.19475062267780458},
      {1.0, 0.4, 1.4114725398426436, 0.65448710612378886},   {1.0, 0.8, 3.1989733244180226, 10.172070234189075},
      {-1.0, 0.05, 1.5855474943721449, 0.60467759702572015}, {-1.0, 0.2, 3.6092217570255185, 3.0240232186273741},
      {-1.0, 0.4, 7.2900918550479466, 9.0699055962244601},   {-1.0, 0.8, 28.70447124418055, 113.60602832255593}};
  const double l = std::sqrt(2.0 / 7.0);
  for (const Value& v : values) {
    const double a = v.sign * l;
    double F = 0.0, xF = 0.0;
    hypergeometric_2f1(a, a + 2.0, 2.0 * a + 1.0, v.x, &F, &xF);
    EXPECT_NEAR(F, v.F, 1e-14 * v.F) << v.sign << " " << v.x;
    EXPECT_NEAR(xF, v.xF, 1e-14 * v.xF) << v.sign << " " << v.x;
  }
  double F = 0.0, xF = 0.0;
  hypergeometric_2f1(l, l + 2.0, 2.0 * l + 1.0, 0.0, &F, &xF);
  EXPECT_EQ(F, 1.0);
  EXPECT_EQ(xF, 0.0);
}

TEST(Invariants, ParaboloidSolutionsSolveRouthsEquations) {
  // in c = cos(beta) = N_z: du/dc = -(2/7) (1 - eps c) w / (2 a c) and
  // dw/dc = -2 a u / (c (1 - eps c)^2), by central differences
  const double a = 1.3, r = 0.2, eps = 2.0 * a * r, h = 1e-5;
  const RouthParaboloid routh(a, r, 1.0);
  for (const double c : {0.3, 0.55, 0.8, 0.97})
    for (int i = 0; i < 2; ++i) {
      const auto at = routh.solutions(c), up = routh.solutions(c + h), down = routh.solutions(c - h);
      const double du = (up.u[i] - down.u[i]) / (2.0 * h), dw = (up.w[i] - down.w[i]) / (2.0 * h);
      EXPECT_NEAR(du, -(2.0 / 7.0) * (1.0 - eps * c) * at.w[i] / (2.0 * a * c), 1e-8 * (1.0 + std::abs(du))) << c;
      EXPECT_NEAR(dw, -2.0 * a * at.u[i] / (c * (1.0 - eps * c) * (1.0 - eps * c)), 1e-8 * (1.0 + std::abs(dw))) << c;
    }
}

TEST(Invariants, RouthsIntegralsStayConstantInTheParaboloid) {
  const Problem p = make_problem(load_scene("paraboloid"));
  ASSERT_EQ(p.invariants().size(), 1u);
  const RunResult run = accurate_run(p);
  const std::vector<double> change = largest_change(*p.invariants()[0], p, run);
  // the run's own accuracy, seen in the energy, bounds what can be asked
  EXPECT_LT(relative_energy_change(p, run), 1e-13);
  for (const double c : change) EXPECT_LT(c, 1e-13);
}

TEST(Invariants, RouthsIntegralsStayConstantInTheSphericalBowl) {
  const Problem p = make_problem(load_scene("bowl-3d"));
  ASSERT_EQ(p.invariants().size(), 1u);
  const RunResult run = accurate_run(p);
  for (const double c : largest_change(*p.invariants()[0], p, run)) EXPECT_LT(c, 1e-13);
}

TEST(Invariants, ChaplyginIntegralsStayConstantOnThePlane) {
  const Problem p = make_problem(load_scene("chaplygin-plane"));
  ASSERT_EQ(p.invariants().size(), 1u);
  const RunResult run = accurate_run(p);
  for (const double c : largest_change(*p.invariants()[0], p, run)) EXPECT_LT(c, 1e-13);
}

TEST(Invariants, RouthsIntegralsDriftOffTheSymmetry) {
  // the same formulas along accurate runs where they are no integrals: a
  // landscape without the symmetry of revolution, and an anisotropic ball
  // in the paraboloid itself; the energy is kept as well as above
  const Scene base = load_scene("paraboloid");
  const RouthParaboloid routh(base.params.at("a"), base.ball.radius, base.ball.mass);
  for (const char* scene : {"paraboloid-perturbed", "paraboloid-chaplygin"}) {
    SCOPED_TRACE(scene);
    const Problem p = make_problem(load_scene(scene));
    EXPECT_TRUE(p.invariants().empty());
    const RunResult run = accurate_run(p);
    EXPECT_LT(relative_energy_change(p, run), 1e-13);
    const std::vector<double> change = largest_change(routh, p, run);
    EXPECT_GT(*std::max_element(change.begin(), change.end()), 1e-2);
  }
  // and omega . N is no integral of a paraboloid
  const Problem p = make_problem(load_scene("paraboloid"));
  const RunResult run = accurate_run(p);
  const RouthSphere sphere(1.0, base.ball.radius, base.ball.mass);
  EXPECT_GT(largest_change(sphere, p, run)[0], 1e-2);
}

// --- what a scene may claim ---

std::string scene_text(const std::string& landscape, const std::string& params, const std::string& invariants,
                       const std::string& ball = R"({ "radius": 0.1, "mass": 1.0 })") {
  return R"({ "name": "t", "landscape": ")" + landscape + R"(", "params": )" + params + R"(, "ball": )" + ball +
         R"(, "start": { "contact": [0.3, 0.0], "velocity": [0.0, 0.5] }, "t_end": 1.0, "invariants": )" + invariants +
         "}";
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Invariants, ASceneMayClaimOnlyWhatItsLandscapeHas) {
  const std::string paraboloid = "a*(x^2 + y^2)";
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", R"(["routh-paraboloid"])")), "no error");
  EXPECT_EQ(error_of(scene_text("a*(x^2 + y^2) + b*x^2*y^2", R"({ "a": 1.0, "b": 2.0 })", R"(["routh-paraboloid"])")),
            "'invariants': the landscape is not the paraboloid f = a*(x^2 + y^2) with a = 1 (at x = 0.3, y = -0.2)");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", R"(["routh-paraboloid"])",
                                R"({ "radius": 0.1, "mass": 1.0, "inertia": [0.003, 0.004, 0.005] })")),
            "'invariants': 'routh-paraboloid' holds for the homogeneous ball; a scene with ball.inertia does not "
            "have it");
  EXPECT_EQ(error_of(scene_text("c*(x^2 + y^2)", R"({ "c": 1.0 })", R"(["routh-paraboloid"])")),
            "'invariants': 'routh-paraboloid' needs the param 'a' (the paraboloid f = a*(x^2 + y^2)) under \"params\"");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", R"(["routh-sphere"])")),
            "'invariants': 'routh-sphere' needs the param 'rho' (the radius of the bowl f = rho - sqrt(rho^2 - x^2 - "
            "y^2)) under \"params\"");
  EXPECT_EQ(error_of(scene_text("rho - sqrt(rho^2 - x^2 - y^2)", R"({ "rho": 1.0 })", R"(["routh-paraboloid"])")),
            "'invariants': 'routh-paraboloid' needs the param 'a' (the paraboloid f = a*(x^2 + y^2)) under \"params\"");
  EXPECT_EQ(error_of(scene_text("-s*y", R"({ "s": 0.2 })", R"(["chaplygin-plane"])")),
            "'invariants': the landscape is not a horizontal plane f = const (at x = 0, y = 0)");
  EXPECT_EQ(error_of(scene_text("0*x", "{}", R"(["chaplygin-plane"])",
                                R"({ "radius": 0.1, "mass": 1.0, "inertia": [0.003, 0.004, 0.005] })")),
            "no error");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", R"(["routh"])")),
            "'invariants': unknown invariant 'routh' (known: chaplygin-plane, routh-paraboloid, routh-sphere)");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", R"(["routh-paraboloid", "routh-paraboloid"])")),
            "'invariants': the invariant 'routh-paraboloid' is named more than once");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", R"("routh-paraboloid")")),
            "'invariants': must be an array of names, not string");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 1.0 })", "[3]")), "'invariants': must be a string, not number");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": -1.0 })", R"(["routh-paraboloid"])")),
            "'invariants': 'routh-paraboloid' needs a bowl, a > 0, not a = -1");
  EXPECT_EQ(error_of(scene_text("a*(x^2 + y^2) + 0*rho", R"({ "a": 1.0, "rho": 1.0 })", R"(["routh-sphere"])")),
            "'invariants': the landscape is not the spherical bowl f = rho - sqrt(rho^2 - x^2 - y^2) with rho = 1 (at "
            "x = 0, y = 0)");
  EXPECT_EQ(error_of(scene_text("rho - sqrt(rho^2 - x^2 - y^2)", R"({ "rho": 1.0 })", R"(["routh-sphere"])")),
            "no error");
  EXPECT_EQ(error_of(scene_text(paraboloid, R"({ "a": 6.0 })", R"(["routh-paraboloid"])")),
            "'invariants': 'routh-paraboloid' needs the ball to fit the bottom of the bowl, 2 a r < 1, not 1.2");
}

TEST(Invariants, ShippedScenesDeclareThem) {
  EXPECT_EQ(read_shipped_scene("paraboloid").invariants, std::vector<std::string>{"routh-paraboloid"});
  EXPECT_EQ(read_shipped_scene("bowl-3d").invariants, std::vector<std::string>{"routh-sphere"});
  EXPECT_EQ(read_shipped_scene("chaplygin-plane").invariants, std::vector<std::string>{"chaplygin-plane"});
  EXPECT_TRUE(read_shipped_scene("paraboloid-perturbed").invariants.empty());
}

// Which integrals show structure (docs/model.md): the loader exposes each
// one's kind, and the kinematic ones are kept by methods with no structure
// at all, while the dynamical ones are not.
TEST(Invariants, KinematicIntegralsAreMarkedAndKeptByAnyMethod) {
  struct Expect {
    const char* scene;
    std::vector<std::string> names;
    std::vector<IntegralKind> kinds;
  };
  const IntegralKind dyn = IntegralKind::dynamical, kin = IntegralKind::kinematic;
  for (const Expect& e : {Expect{"paraboloid", {"routh-paraboloid.J1", "routh-paraboloid.J2"}, {dyn, dyn}},
                          Expect{"bowl-3d", {"routh-sphere.omega.N", "routh-sphere.J"}, {dyn, kin}},
                          Expect{"chaplygin-plane", {"chaplygin-plane.K.K", "chaplygin-plane.K.N"}, {kin, kin}}}) {
    SCOPED_TRACE(e.scene);
    const Problem p = make_problem(load_scene(e.scene));
    ASSERT_EQ(p.invariants().size(), 1u);
    EXPECT_EQ(p.invariants()[0]->kinds(), e.kinds);
    const InvariantMeter meter(p);
    EXPECT_EQ(meter.names(), e.names);
    EXPECT_EQ(meter.kinds(), e.kinds);
  }
  EXPECT_EQ(kind_name(IntegralKind::kinematic), "kinematic");
  EXPECT_EQ(kind_name(IntegralKind::dynamical), "dynamical");

  // the spherical bowl's J is identically (5/7) v_z / (m r^2), at any state,
  // on the trajectory or not
  const Problem bowl = make_problem(load_scene("bowl-3d"));
  const BallParams& b = bowl.model().params();
  for (const FlatState& start : {bowl.y0(), FlatState(bowl.y0() + 0.1 * FlatState::Ones())}) {
    FlatState y = start;
    y.segment<3>(kOffsetV) += Vec3(0.3, -0.7, 0.2);
    double value[2], magnitude[2];
    bowl.invariants()[0]->at(y, value, magnitude);
    EXPECT_NEAR(value[1], 5.0 / 7.0 * y[kOffsetV + 2] / (b.mass * b.radius * b.radius), 1e-14 * magnitude[1]);
  }
  // so Euler keeps it to rounding with an energy error of order 1, and
  // omega . N not: only the dynamical one tells the methods apart
  // (one output: the end)
  const auto fixed = [](double h, double t_end) {
    RunOptions o;
    o.h = h;
    o.t_end = t_end;
    return o;
  };
  const RunResult euler = find_integrator("euler").integrate(bowl, fixed(0.01, 5.0));
  ASSERT_EQ(euler.status, Status::ok) << euler.message;
  const std::vector<double> bowl_change = largest_change(*bowl.invariants()[0], bowl, euler);
  EXPECT_LT(bowl_change[1], 1e-13);
  EXPECT_GT(bowl_change[0], 1e-2);
  EXPECT_GT(relative_energy_change(bowl, euler), 0.5);

  // on the plane v's rate is 0 in F: a Lie-group method of order 1 keeps
  // M . M and M . gamma to rounding with a large energy error
  const Problem plane = make_problem(load_scene("chaplygin-plane"));
  const RunResult exp_euler = find_integrator("exp-euler").integrate(plane, fixed(1.0 / 64, 3.0));
  ASSERT_EQ(exp_euler.status, Status::ok) << exp_euler.message;
  for (const double c : largest_change(*plane.invariants()[0], plane, exp_euler)) EXPECT_LT(c, 1e-13);
  EXPECT_GT(relative_energy_change(plane, exp_euler), 1e-3);
}

}  // namespace
}  // namespace rb

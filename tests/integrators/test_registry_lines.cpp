// A registry line, list.push_back(<way of stepping>(<method data>, "<name>",
// <controller>)) (docs/extending.md): the name and the controller it gives
// reach the method, the data gives the method's facts, and a controller the
// way of stepping does not take is an InputError naming the method, the way
// and the controller. Here for the ways of stepping whose data is not a
// tableau (baselines, discrete gradient, Lagrange-d'Alembert, symmetric,
// odeint, GSL).
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/baselines/baselines.hpp"
#include "integrators/families/discrete_gradient/discrete_gradient.hpp"
#include "integrators/families/gsl/gsl.hpp"
#include "integrators/families/lagrange_dalembert/lagrange_dalembert.hpp"
#include "integrators/families/odeint/odeint.hpp"
#include "integrators/families/symmetric/gauss.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "tests/integrators/fixtures.hpp"

namespace rb {
namespace {

using Make = std::function<std::unique_ptr<Integrator>(const std::string& name, const std::string& controller)>;

// A way of stepping with its data bound, the registry method it makes and
// the controller that method has.
struct Line {
  const char* registered;
  const char* controller;
  Make make;
};

const std::string constant = kConstantController, library = kLibraryController;

std::vector<Line> lines() {
  using S = OdeintStepper;
  return {
      {"rk4-projected-svd", kConstantController,
       [](const std::string& n, const std::string& c) { return rk4_baseline(RotationFix::project_svd, n, c); }},
      {"rk4-quaternion", kConstantController,
       [](const std::string& n, const std::string& c) { return rk4_baseline(RotationFix::unit_quaternion, n, c); }},
      {"dg2", kConstantController,
       [](const std::string& n, const std::string& c) {
         return discrete_gradient_method(DiscreteGradient::gonzalez_midpoint, n, c);
       }},
      {"dla2", kConstantController,
       [](const std::string& n, const std::string& c) {
         return lagrange_dalembert_method(DiscreteConstraint::trapezoidal, n, c);
       }},
      {"gauss4", kConstantController, [](const std::string& n, const std::string& c) { return gauss_method(2, n, c); }},
      {"gauss2-tj6", kConstantController,
       [](const std::string& n, const std::string& c) { return midpoint_composition(6, n, c); }},
      {"lie-gauss2-tj4", kConstantController,
       [](const std::string& n, const std::string& c) { return lie_midpoint_composition(4, n, c); }},
      {"odeint-abm5", kConstantController,
       [](const std::string& n, const std::string& c) { return odeint_method(S::abm5, n, c); }},
      {"odeint-dopri5", kConstantController,
       [](const std::string& n, const std::string& c) { return odeint_method(S::dopri5, n, c); }},
      {"odeint-dopri5-adaptive", kLibraryController,
       [](const std::string& n, const std::string& c) { return odeint_method(S::dopri5, n, c); }},
      {"odeint-bulirsch-stoer", kLibraryController,
       [](const std::string& n, const std::string& c) { return odeint_method(S::bulirsch_stoer, n, c); }},
      {"gsl-rkck", kConstantController,
       [](const std::string& n, const std::string& c) { return gsl_method("rkck", n, c); }},
      {"gsl-rkck-adaptive", kLibraryController,
       [](const std::string& n, const std::string& c) { return gsl_method("rkck", n, c); }},
      {"gsl-msbdf-adaptive", kLibraryController,
       [](const std::string& n, const std::string& c) { return gsl_method("msbdf", n, c); }},
  };
}

// A line made under another name is the registered method in every fact
// but the name: the name is the line's, the controller the line's, the rest
// the data's.
TEST(RegistryLines, TheNameAndTheControllerOfALineReachTheMethod) {
  for (const Line& line : lines()) {
    const std::unique_ptr<Integrator> made = line.make("a-line-of-mine", line.controller);
    const MethodInfo& mine = made->info();
    const MethodInfo& shipped = find_integrator(line.registered).info();
    EXPECT_EQ(mine.name, "a-line-of-mine") << line.registered;
    EXPECT_EQ(mine.controller, line.controller) << line.registered;
    EXPECT_EQ(shipped.controller, line.controller) << line.registered;
    EXPECT_EQ(mine.adaptive, std::string(line.controller) == kLibraryController) << line.registered;
    EXPECT_EQ(mine.family, shipped.family) << line.registered;
    EXPECT_EQ(mine.declared_order, shipped.declared_order) << line.registered;
    EXPECT_EQ(mine.rotation_order, shipped.rotation_order) << line.registered;
    EXPECT_EQ(mine.adaptive, shipped.adaptive) << line.registered;
    EXPECT_EQ(mine.needs_jacobian, shipped.needs_jacobian) << line.registered;
    EXPECT_EQ(mine.description, shipped.description) << line.registered;
    EXPECT_EQ(mine.tableau, shipped.tableau) << line.registered;
    EXPECT_EQ(mine.on_group, shipped.on_group) << line.registered;
    EXPECT_EQ(mine.newton_tol, shipped.newton_tol) << line.registered;
  }
}

// ... and steps as the registered one, to the bit.
TEST(RegistryLines, ALineMadeAgainStepsAsTheRegisteredMethod) {
  for (const Line& line : lines()) {
    const bool adaptive = std::string(line.controller) == kLibraryController;
    const RunOptions options = adaptive ? testing::tolerance_every(1e-6, 0.25, 0.5) : testing::fixed(0.05, 0.5);
    const RunResult mine = line.make("a-line-of-mine", line.controller)->integrate(testing::valley(), options);
    const RunResult shipped = find_integrator(line.registered).integrate(testing::valley(), options);
    ASSERT_EQ(mine.status, Status::ok) << line.registered << ": " << mine.message;
    EXPECT_EQ(mine.final_state, shipped.final_state) << line.registered;
    EXPECT_EQ(mine.cost.rhs_evals, shipped.cost.rhs_evals) << line.registered;
  }
}

// The exact message, under the key "controller".
void expect_refused(const Make& make, const std::string& name, const std::string& controller,
                    const std::string& message) {
  try {
    (void)make(name, controller);
    ADD_FAILURE() << name << " made with controller '" << controller << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "controller") << name;
    EXPECT_EQ(e.message(), message) << name;
  }
}

TEST(RegistryLines, AControllerTheWayOfSteppingDoesNotTakeIsAnInputErrorNamingIt) {
  using S = OdeintStepper;
  expect_refused(
      [](const std::string& n, const std::string& c) { return rk4_baseline(RotationFix::project_newton_schulz, n, c); },
      "rk4-projected", "pi", "'rk4-projected': a fixed-step baseline takes the controller 'constant' only, not 'pi'");
  expect_refused(
      [](const std::string& n, const std::string& c) {
        return discrete_gradient_method(DiscreteGradient::gonzalez_midpoint, n, c);
      },
      "dg2", library, "'dg2': the discrete-gradient method takes the controller 'constant' only, not 'library'");
  expect_refused([](const std::string& n,
                    const std::string& c) { return lagrange_dalembert_method(DiscreteConstraint::trapezoidal, n, c); },
                 "dla2", "pid",
                 "'dla2': the discrete Lagrange-d'Alembert method takes the controller 'constant' only, not 'pid'");
  expect_refused([](const std::string& n, const std::string& c) { return gauss_method(1, n, c); }, "gauss2", "i",
                 "'gauss2': Gauss collocation takes the controller 'constant' only, not 'i'");
  expect_refused([](const std::string& n, const std::string& c) { return midpoint_composition(4, n, c); }, "gauss2-tj4",
                 "pi",
                 "'gauss2-tj4': the composed implicit midpoint rule takes the controller 'constant' only, not 'pi'");
  expect_refused([](const std::string& n, const std::string& c) { return lie_midpoint_composition(2, n, c); },
                 "lie-gauss2", library,
                 "'lie-gauss2': the Lie midpoint rule takes the controller 'constant' only, not 'library'");
  expect_refused([](const std::string& n, const std::string& c) { return odeint_method(S::abm4, n, c); }, "odeint-abm4",
                 library,
                 "'odeint-abm4': odeint's adams_bashforth_moulton<4> (no error estimate) takes the controller "
                 "'constant' only, not 'library'");
  expect_refused([](const std::string& n, const std::string& c) { return odeint_method(S::bulirsch_stoer, n, c); },
                 "odeint-bulirsch-stoer", constant,
                 "'odeint-bulirsch-stoer': odeint's bulirsch_stoer (adaptive only) takes the controller 'library' "
                 "only, not 'constant'");
  expect_refused([](const std::string& n, const std::string& c) { return odeint_method(S::dopri5, n, c); },
                 "odeint-dopri5-adaptive", "pi",
                 "'odeint-dopri5-adaptive': odeint's runge_kutta_dopri5 takes the controller 'constant' or "
                 "'library', not 'pi'");
  expect_refused([](const std::string& n, const std::string& c) { return gsl_method("msbdf", n, c); }, "gsl-msbdf",
                 constant,
                 "'gsl-msbdf': GSL's msbdf (variable order: adaptive only) takes the controller 'library' only, not "
                 "'constant'");
  expect_refused([](const std::string& n, const std::string& c) { return gsl_method("rkf45", n, c); },
                 "gsl-rkf45-adaptive", "pid",
                 "'gsl-rkf45-adaptive': GSL's rkf45 takes the controller 'constant' or 'library', not 'pid'");
}

// Method data a way of stepping has no method for is refused, not
// defaulted, under the key "integrator".
TEST(RegistryLines, DataWithNoMethodIsAnInputErrorNamingIt) {
  const auto refused = [](const std::function<void()>& make, const std::string& message) {
    try {
      make();
      ADD_FAILURE() << "made: " << message;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "integrator") << message;
      EXPECT_EQ(e.message(), message);
    }
  };
  refused([] { (void)gauss_method(4, "gauss8", constant); },
          "'gauss8': Gauss collocation has 1, 2 or 3 stages here, not 4");
  refused([] { (void)midpoint_composition(3, "gauss2-tj3", constant); },
          "'gauss2-tj3': the midpoint rule is composed to order 2, 4 or 6 here, not 3");
  refused([] { (void)lie_midpoint_composition(8, "lie-gauss2-tj8", constant); },
          "'lie-gauss2-tj8': the midpoint rule is composed to order 2, 4 or 6 here, not 8");
  refused([] { (void)gsl_method("rk5", "gsl-rk5", constant); },
          "GSL has no odeiv2 stepper 'rk5' (known: rk2, rk4, rkf45, rkck, rk8pd, rk1imp, rk2imp, rk4imp, bsimp, "
          "msadams, msbdf)");
}

}  // namespace
}  // namespace rb

#include "integrators/registry.hpp"

#include "integrators/controllers/controller.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/cf3.hpp"
#include "integrators/methods/cf4.hpp"
#include "integrators/methods/cg3.hpp"
#include "integrators/methods/cg4a.hpp"
#include "integrators/methods/cg5a.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/methods/verner76.hpp"
#include "integrators/methods/verner98.hpp"
#include "integrators/steppers/baselines.hpp"
#include "integrators/steppers/discrete_gradient.hpp"
#include "integrators/steppers/exp_product.hpp"
#include "integrators/steppers/explicit_midpoint.hpp"
#include "integrators/steppers/gauss.hpp"
#include "integrators/steppers/gsl.hpp"
#include "integrators/steppers/lagrange_dalembert.hpp"
#include "integrators/steppers/odeint.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

std::vector<std::unique_ptr<Integrator>> make_registry() {
  std::vector<std::unique_ptr<Integrator>> r;
  auto add = [&](std::unique_ptr<Integrator> integrator) { r.push_back(std::move(integrator)); };
  // One line a method, each a factory's integrator: add(<way of stepping>(
  // <method data>, "<name>", <controller>[, <variant>])), the method data in
  // integrators/methods/, the ways of stepping in integrators/steppers/
  // (docs/extending.md). Methods with no data file of their own (midpoint,
  // the baselines) and the libraries' adapters name their variant only.
  using D = DexpinvKind;
  namespace m = methods;
  const std::string constant = kConstantController, pi = "pi";

  // classical explicit Runge-Kutta on the flat view
  add(rk_method(m::euler(), "euler", constant));
  add(rk_method(m::heun(), "heun", constant));
  add(rk_method(m::kutta3(), "rk3", constant));
  add(rk_method(m::rk4(), "rk4", constant));
  add(rk_method(m::rk38(), "rk38", constant));
  add(explicit_midpoint());  // docs/extending.md's worked example

  // Lie-group methods: exp-Euler and Runge-Kutta-Munthe-Kaas
  add(rkmk_method(m::euler(), "exp-euler", constant));
  add(rkmk_method(m::heun(), "rkmk2", constant));
  add(rkmk_method(m::kutta3(), "rkmk3", constant));
  add(rkmk_method(m::rk4(), "rkmk4", constant));
  add(rkmk_method(m::rk4(), "rkmk4-series", constant, D::truncated));
  add(rkmk_method(m::rk4(), "rkmk4-seminar", constant, D::seminar));

  // --- lie-group adaptive and baselines ---
  // fixed-step RKMK at high order (what order buys), adaptive RKMK on
  // embedded pairs (what adaptivity buys), and the practitioners' fixes
  add(rkmk_method(m::dormand_prince54(), "rkmk5", constant));
  add(rkmk_method(m::fehlberg78(), "rkmk8", constant));
  add(rkmk_method(m::bogacki_shampine32(), "rkmk-bs32-adaptive", pi));
  add(rkmk_method(m::dormand_prince54(), "rkmk-dp54-adaptive", pi));
  add(rkmk_method(m::dormand_prince853(), "rkmk-dp853-adaptive", pi));
  add(rkmk_method(m::fehlberg78(), "rkmk-f78-adaptive", pi));
  add(rkmk_method(m::verner76(), "rkmk-verner7-adaptive", pi));
  add(rkmk_method(m::verner98(), "rkmk-verner9-adaptive", pi));
  // their flat twins: the same embedded pair, PI controller and RMS error
  // norm, on the flat view (dp853's stretched estimate has no flat twin)
  add(rk_method(m::bogacki_shampine32(), "rk-bs32-adaptive", pi));
  add(rk_method(m::dormand_prince54(), "rk-dp54-adaptive", pi));
  add(rk_method(m::fehlberg78(), "rk-f78-adaptive", pi));
  add(rk_method(m::verner76(), "rk-verner7-adaptive", pi));
  add(rk_method(m::verner98(), "rk-verner9-adaptive", pi));
  add(rk4_projected("rk4-projected", Projection::newton_schulz));
  add(rk4_projected("rk4-projected-svd", Projection::svd));
  add(rk4_quaternion("rk4-quaternion"));
  // --- end lie-group adaptive and baselines ---

  // --- commutator-free and Crouch-Grossman ---
  // products of exponentials only (exp_product.hpp); the -reversed variants
  // compose every product the other way round (order 2 in R, and where R
  // feeds back in every component); then rkmk4 with the Cayley map
  add(exp_product_method(m::cf3(), "cf3", constant));
  add(exp_product_method(m::cf4(), "cf4", constant));
  add(exp_product_method(m::cg3(), "cg3", constant));
  add(exp_product_method(m::cg4a(), "cg4a", constant));
  add(exp_product_method(m::cg5a(), "cg5a", constant));
  add(exp_product_method(reversed(m::cf4()), "cf4-reversed", constant));
  add(exp_product_method(reversed(m::cg3()), "cg3-reversed", constant));
  add(exp_product_method(reversed(m::cg4a()), "cg4a-reversed", constant));
  add(exp_product_method(m::cg3_pair(), "cg3-adaptive", pi));
  add(exp_product_method(m::cf4_pair(), "cf4-adaptive", pi));
  add(rkmk_cayley_method(m::rk4(), "rkmk4-cayley", constant));

  // symmetric implicit methods, solved by the suite's simplified Newton
  // (integrators/steppers/gauss.hpp): flat Gauss collocation, and the
  // implicit midpoint rule composed to orders 4 and 6, flat and on the group
  for (const int stages : {1, 2, 3}) add(gauss_method(stages));
  for (const int order : {4, 6}) add(midpoint_composition(order, false));
  for (const int order : {2, 4, 6}) add(midpoint_composition(order, true));
  // the discrete-gradient method: energy conserved to rounding
  add(discrete_gradient_method());
  // the discrete Lagrange-d'Alembert method: variational, symmetric, on SO(3) x R^2
  add(lagrange_dalembert_method());
  // --- end commutator-free and Crouch-Grossman ---

  // --- odeint --- (Boost.Odeint steppers on the flat view)
  add(odeint_euler());
  add(odeint_rk4());
  add(odeint_cash_karp54());
  add(odeint_dopri5());
  add(odeint_fehlberg78());
  add(odeint_abm4());
  add(odeint_abm5());
  add(odeint_dopri5_adaptive());
  add(odeint_cash_karp54_adaptive());
  add(odeint_fehlberg78_adaptive());
  add(odeint_bulirsch_stoer());
  // --- end odeint ---

  // --- gsl --- (GSL odeiv2 steppers on the flat view)
  // fixed step: the one-step methods. msadams, msbdf and bsimp choose
  // their order from a tolerance, so they run adaptive only; rk8pd too,
  // since at fixed steps its error falls from 1e-3 to rounding within three
  // halvings of h, too few for the order test to see order 8
  for (const char* stepper : {"rk2", "rk4", "rkf45", "rkck", "rk1imp", "rk2imp", "rk4imp"})
    add(gsl_method(stepper, GslDrive::fixed_step));
  for (const char* stepper : {"rk2", "rkf45", "rkck", "rk8pd", "rk4imp", "bsimp", "msadams", "msbdf"})
    add(gsl_method(stepper, GslDrive::adaptive));
  // --- end gsl ---
  return r;
}

std::vector<std::unique_ptr<Integrator>>& mutable_registry() {
  static std::vector<std::unique_ptr<Integrator>> all = make_registry();
  return all;
}

}  // namespace

const std::vector<std::unique_ptr<Integrator>>& registry() { return mutable_registry(); }

void add_integrator(std::unique_ptr<Integrator> integrator, const std::string& key) {
  for (const auto& existing : registry())
    if (existing->name() == integrator->name())
      throw InputError("integrator '" + integrator->name() + "' is already registered", key);
  mutable_registry().push_back(std::move(integrator));
}

const Integrator& find_integrator(std::string_view name) {
  for (const auto& integrator : registry())
    if (integrator->name() == name) return *integrator;
  throw InputError("unknown integrator '" + std::string(name) + "' (`rollbench list` shows them all)", "integrator");
}

}  // namespace rb

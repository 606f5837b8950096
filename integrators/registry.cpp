#include "integrators/registry.hpp"

#include "integrators/steppers/baselines.hpp"
#include "integrators/steppers/commutator_free.hpp"
#include "integrators/steppers/crouch_grossman.hpp"
#include "integrators/steppers/exp_product_adaptive.hpp"
#include "integrators/steppers/gsl.hpp"
#include "integrators/steppers/explicit_midpoint.hpp"
#include "integrators/steppers/munthe_kaas.hpp"
#include "integrators/steppers/odeint.hpp"
#include "integrators/steppers/rkmk_cayley.hpp"
#include "integrators/steppers/runge_kutta.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

std::vector<std::unique_ptr<Integrator>> make_registry() {
  std::vector<std::unique_ptr<Integrator>> r;
  auto add = [&](std::unique_ptr<Integrator> integrator) { r.push_back(std::move(integrator)); };
  using D = DexpinvKind;
  namespace t = methods;

  // classical explicit Runge-Kutta on the flat view
  add(std::make_unique<RungeKutta>(t::euler()));
  add(std::make_unique<RungeKutta>(t::heun()));
  add(std::make_unique<RungeKutta>(t::kutta3()));
  add(std::make_unique<RungeKutta>(t::rk4()));
  add(std::make_unique<RungeKutta>(t::rk38()));
  add(std::make_unique<ExplicitMidpoint>());  // docs/extending.md's worked example

  // Lie-group methods: exp-Euler and Runge-Kutta-Munthe-Kaas
  add(std::make_unique<MuntheKaas>(t::euler(), "exp-euler"));
  add(std::make_unique<MuntheKaas>(t::heun(), "rkmk2"));
  add(std::make_unique<MuntheKaas>(t::kutta3(), "rkmk3"));
  add(std::make_unique<MuntheKaas>(t::rk4(), "rkmk4"));
  add(std::make_unique<MuntheKaas>(t::rk4(), "rkmk4-series", D::truncated));
  add(std::make_unique<MuntheKaas>(t::rk4(), "rkmk4-seminar", D::seminar));

  // --- lie-group adaptive and baselines ---
  // fixed-step RKMK at high order (what order buys), adaptive RKMK on
  // embedded pairs (what adaptivity buys), and the practitioners' fixes
  // (one line names a tableau, a way of stepping and a controller)
  const std::string constant = kConstantController, pi = "pi";
  add(rkmk_method(t::dormand_prince54(), "rkmk5", constant));
  add(rkmk_method(t::fehlberg78(), "rkmk8", constant));
  add(rkmk_method(t::bogacki_shampine32(), "rkmk-bs32-adaptive", pi));
  add(rkmk_method(t::dormand_prince54(), "rkmk-dp54-adaptive", pi));
  add(rkmk_method(t::dormand_prince853(), "rkmk-dp853-adaptive", pi));
  add(rkmk_method(t::fehlberg78(), "rkmk-f78-adaptive", pi));
  add(std::make_unique<Rk4Projected>());
  add(std::make_unique<Rk4Projected>(Projection::svd));
  add(std::make_unique<Rk4Quaternion>());
  // --- end lie-group adaptive and baselines ---

  // --- commutator-free and Crouch-Grossman ---
  // products of exponentials only (exp_product.hpp); the -reversed variants
  // compose every product the other way round (order 2 in R, and where R
  // feeds back in every component); then rkmk4 with the Cayley map
  add(std::make_unique<ExpProductMethod>(schemes::cf4()));
  add(std::make_unique<ExpProductMethod>(schemes::cg3()));
  add(std::make_unique<ExpProductMethod>(schemes::cg4a()));
  add(std::make_unique<ExpProductMethod>(reversed(schemes::cf4(), "cf4-reversed")));
  add(std::make_unique<ExpProductMethod>(reversed(schemes::cg3(), "cg3-reversed")));
  add(std::make_unique<ExpProductMethod>(reversed(schemes::cg4a(), "cg4a-reversed")));
  add(exp_product_adaptive(schemes::cg3_pair()));
  add(std::make_unique<MuntheKaasCayley>(t::rk4(), "rkmk4-cayley"));
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
    add(std::make_unique<GslIntegrator>(stepper, GslDrive::fixed_step));
  for (const char* stepper : {"rk2", "rkf45", "rkck", "rk8pd", "rk4imp", "bsimp", "msadams", "msbdf"})
    add(std::make_unique<GslIntegrator>(stepper, GslDrive::adaptive));
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

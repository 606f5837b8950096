#include "integrators/families/odeint/odeint.hpp"

#include <algorithm>
#include <boost/numeric/odeint/stepper/adams_bashforth_moulton.hpp>
#include <boost/numeric/odeint/stepper/bulirsch_stoer.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/euler.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_cash_karp54.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_fehlberg78.hpp>
#include <boost/numeric/odeint/util/odeint_error.hpp>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "integrators/adaptive_loops.hpp"
#include "integrators/controllers/controller.hpp"
#include "integrators/driver.hpp"
#include "integrators/steppers/stepped_method.hpp"

namespace rb {

namespace {

namespace ode = boost::numeric::odeint;

void load(const FlatState& y, OdeintState& x) { std::copy_n(y.data(), kFlatSize, x.begin()); }
void store(const OdeintState& x, FlatState& y) { std::copy_n(x.begin(), kFlatSize, y.data()); }

// An adapter's facts: its registry name, declared order and line for
// `rollbench list`, in the family "odeint"; tableau: the registry's name of
// the Butcher tableau the stepper uses, where a Lie-group method shares it
// (MethodInfo::tableau).
MethodInfo odeint_facts(std::string name, int order, std::string description, bool adaptive, std::string tableau) {
  return {.name = std::move(name),
          .family = "odeint",
          .declared_order = order,
          .adaptive = adaptive,
          .description = std::move(description),
          .tableau = std::move(tableau)};
}

// ---- fixed step ----

// A one-step stepper's do_step on the run's own copy x of the state; the
// stepper lives in the run (stepped_method makes one per run).
// drive_fixed_step always passes back the state a step returned (a run stops
// at a bad step), so x already holds it: one copy a step, out to the driver.
// dopri5 keeps its last derivative (FSAL), sound for the same reason.
template <class Stepper>
struct OdeintStep {
  const Problem* problem;
  Stepper stepper{};
  OdeintState x{};

  explicit OdeintStep(const Problem& p) : problem(&p) { load(p.y0(), x); }
  void operator()(const FlatState& /*y, held in x*/, FlatState& next, double t, double h, Cost& cost) {
    stepper.do_step(OdeintSystem{problem, &cost}, x, t, h);
    store(x, next);
  }
};

// Adams-Bashforth-Moulton keeps the derivatives of its last Steps steps and
// assumes they were taken with the current h. drive_fixed_step changes h only
// between two outputs whose spacing is not a multiple of h; there the history
// is dropped and the stepper restarts with Steps - 1 runge_kutta4 steps (4
// evaluations each, then 2 a step). Changes at rounding level (spacings that
// are multiples of h, computed as span / n) keep the history.
template <std::size_t Steps>
struct OdeintAbmStep {
  const Problem* problem;
  ode::adams_bashforth_moulton<Steps, OdeintState> stepper{};
  OdeintState x{};         // the state, as in OdeintStep
  double h_history = 0.0;  // the step the stored derivatives belong to

  explicit OdeintAbmStep(const Problem& p) : problem(&p) { load(p.y0(), x); }
  void operator()(const FlatState& /*y, held in x*/, FlatState& next, double t, double h, Cost& cost) {
    if (std::abs(h - h_history) > 1e-12 * h) {
      stepper.reset();
      h_history = h;
    }
    stepper.do_step(OdeintSystem{problem, &cost}, x, t, h);
    store(x, next);
  }
};

// ---- adaptive ----

// Odeint's own failures as statuses. Its checkers throw them only from its
// integrate functions and dense-output steppers, which these adapters do not
// use (they drive try_step themselves), so this is a safety net.
template <class F>
auto guarded(F&& f) {
  try {
    return f();
  } catch (const ode::step_adjustment_error& e) {
    throw StepFailure(Status::step_underflow, std::string("odeint: ") + e.what());
  } catch (const ode::no_progress_error& e) {
    throw StepFailure(Status::step_underflow, std::string("odeint: ") + e.what());
  }
}

using BulirschStoer = ode::bulirsch_stoer<OdeintState>;

// A controller with odeint's default error norm at the run's tolerances.
// (controlled_runge_kutta copies a default-made stepper whose scratch arrays
// are not initialised yet; GCC warns about that copy, which is harmless.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
template <class Controlled>
Controlled make_controlled(const Tolerances& tol) {
  if constexpr (std::is_same_v<Controlled, BulirschStoer>) return BulirschStoer(tol.atol(), tol.rtol());
  else return Controlled(typename Controlled::error_checker_type(tol.atol(), tol.rtol()));
}
#pragma GCC diagnostic pop

// A controlled stepper (controlled_runge_kutta or bulirsch_stoer) for
// drive_own_controller: try_step from the current state; F at that state is
// computed once and reused by the attempts after a rejection.
template <class Controlled>
class ControlledStepper {
 public:
  static constexpr bool dense_output = false;

  ControlledStepper(const Problem& problem, const Tolerances& tol)
      : controlled_(make_controlled<Controlled>(tol)), problem_(&problem) {
    load(problem.y0(), x_);
  }

  Attempt attempt(double t, double& h, Cost& cost) {
    const OdeintSystem sys{problem_, &cost};
    if (!dxdt_current_) sys(x_, dxdt_, t);
    dxdt_current_ = true;
    const ode::controlled_step_result r = guarded([&] { return controlled_.try_step(sys, x_, dxdt_, t, h); });
    if (r != ode::success) return Attempt::rejected;
    dxdt_current_ = false;
    return Attempt::accepted;
  }
  // undoes an accepted attempt the driver refused (a stage beyond a limit)
  void restore(const FlatState& y) {
    load(y, x_);
    dxdt_current_ = false;
    if constexpr (std::is_same_v<Controlled, BulirschStoer>) controlled_.reset();
  }
  void state(FlatState& y) const { store(x_, y); }
  void interpolate(double, FlatState&) const {}

 private:
  Controlled controlled_;
  const Problem* problem_;
  OdeintState x_, dxdt_;
  bool dxdt_current_ = false;  // dxdt_ = F(x_)
};

// Controlled dopri5 with its dense output: the loop of odeint's
// dense_output_runge_kutta, written out so that rejected attempts are counted
// and the budget holds. Two (state, derivative) slots alternate: the current
// one and the one before the last accepted step.
class DenseDopri5 {
 public:
  static constexpr bool dense_output = true;
  using Controlled = ode::controlled_runge_kutta<ode::runge_kutta_dopri5<OdeintState>>;

  DenseDopri5(const Problem& problem, const Tolerances& tol)
      : controlled_(make_controlled<Controlled>(tol)), problem_(&problem) {
    load(problem.y0(), x_[0]);
  }

  Attempt attempt(double t, double& h, Cost& cost) {
    const OdeintSystem sys{problem_, &cost};
    just_accepted_ = false;
    if (!started_) sys(x_[cur_], dxdt_[cur_], t);
    started_ = true;
    const int other = 1 - cur_;
    double t_step = t;
    const ode::controlled_step_result r =
        guarded([&] { return controlled_.try_step(sys, x_[cur_], dxdt_[cur_], t_step, x_[other], dxdt_[other], h); });
    if (r != ode::success) return Attempt::rejected;
    t_old_ = t;
    t_new_ = t_step;
    cur_ = other;
    just_accepted_ = true;
    return Attempt::accepted;
  }
  // undoes an attempt the driver refused: after an accepted one the slot
  // before it still holds y and F(y); after a failed one cur_ still does
  void restore(const FlatState& /*y, in a slot*/) {
    if (just_accepted_) cur_ = 1 - cur_;
    just_accepted_ = false;
  }
  void state(FlatState& y) const { store(x_[cur_], y); }
  // dopri5's own 4th-order interpolant; uses the stages of the last step.
  void interpolate(double t, FlatState& y) const {
    const int old = 1 - cur_;
    OdeintState out;
    controlled_.stepper().calc_state(t, out, x_[old], dxdt_[old], t_old_, x_[cur_], dxdt_[cur_], t_new_);
    store(out, y);
  }

 private:
  Controlled controlled_;
  const Problem* problem_;
  OdeintState x_[2], dxdt_[2];
  int cur_ = 0;
  bool started_ = false;
  bool just_accepted_ = false;  // the last attempt moved cur_
  double t_old_ = 0.0, t_new_ = 0.0;
};

template <class Stepper>
class OdeintAdaptive final : public Integrator {
 public:
  explicit OdeintAdaptive(MethodInfo info) : Integrator(std::move(info)) {}
  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    Stepper stepper(problem, options.tolerances);
    return drive_own_controller(problem, options, declared_order(), stepper);
  }
};

template <class Rk>
using Controlled = ControlledStepper<ode::controlled_runge_kutta<Rk>>;

// ---- the steppers, by OdeintStepper ----

using MakeIntegrator = std::unique_ptr<Integrator> (*)(MethodInfo);

// A fixed-step stepper made an integrator by stepped_method, like every
// fixed-step method.
template <class Step>
std::unique_ptr<Integrator> fixed_with(MethodInfo info) {
  return stepped_method(std::move(info), [](const Problem& problem) { return Step(problem); });
}

template <class Stepper>
std::unique_ptr<Integrator> adaptive_with(MethodInfo info) {
  return std::make_unique<OdeintAdaptive<Stepper>>(std::move(info));
}

// What the suite knows of each odeint stepper: odeint's name, the declared
// order (that of the solution it advances with; extrapolation has no single
// order, 8 is what it is declared and guesses its first step with), the
// registry's name of its Butcher tableau where a Lie-group method shares it
// (MethodInfo::tableau), and per drive the description and the integrator,
// nullptr where it has no such drive (no error estimate: fixed steps only;
// extrapolation: adaptive only).
struct OdeintKind {
  OdeintStepper stepper;
  const char* odeint_name;
  int order;
  const char* tableau;
  const char* fixed_description;
  MakeIntegrator fixed;
  const char* adaptive_description;
  MakeIntegrator adaptive;
};

// clang-format off
const OdeintKind kKinds[] = {
  {OdeintStepper::euler, "euler", 1, "euler",
   "Boost.Odeint euler (explicit Euler) on the flat view",
   fixed_with<OdeintStep<ode::euler<OdeintState>>>, nullptr, nullptr},
  {OdeintStepper::rk4, "runge_kutta4", 4, "rk4",
   "Boost.Odeint runge_kutta4 (classic RK4, 4 evaluations a step) on the flat view",
   fixed_with<OdeintStep<ode::runge_kutta4<OdeintState>>>, nullptr, nullptr},
  {OdeintStepper::cash_karp54, "runge_kutta_cash_karp54", 5, "",
   "Boost.Odeint runge_kutta_cash_karp54 at fixed step (5th-order solution)",
   fixed_with<OdeintStep<ode::runge_kutta_cash_karp54<OdeintState>>>,
   "Boost.Odeint controlled runge_kutta_cash_karp54",
   adaptive_with<Controlled<ode::runge_kutta_cash_karp54<OdeintState>>>},
  {OdeintStepper::dopri5, "runge_kutta_dopri5", 5, "dp54",
   "Boost.Odeint runge_kutta_dopri5 at fixed step (5th order, FSAL)",
   fixed_with<OdeintStep<ode::runge_kutta_dopri5<OdeintState>>>,
   "Boost.Odeint controlled runge_kutta_dopri5 with dense output",
   adaptive_with<DenseDopri5>},
  {OdeintStepper::fehlberg78, "runge_kutta_fehlberg78", 8, "f78",
   "Boost.Odeint runge_kutta_fehlberg78 at fixed step (8th-order solution)",
   fixed_with<OdeintStep<ode::runge_kutta_fehlberg78<OdeintState>>>,
   "Boost.Odeint controlled runge_kutta_fehlberg78",
   adaptive_with<Controlled<ode::runge_kutta_fehlberg78<OdeintState>>>},
  {OdeintStepper::abm4, "adams_bashforth_moulton<4>", 4, "",
   "Boost.Odeint adams_bashforth_moulton<4> (PECE), started with runge_kutta4",
   fixed_with<OdeintAbmStep<4>>, nullptr, nullptr},
  {OdeintStepper::abm5, "adams_bashforth_moulton<5>", 5, "",
   "Boost.Odeint adams_bashforth_moulton<5> (PECE), started with runge_kutta4",
   fixed_with<OdeintAbmStep<5>>, nullptr, nullptr},
  {OdeintStepper::bulirsch_stoer, "bulirsch_stoer", 8, "",
   nullptr, nullptr,
   "Boost.Odeint bulirsch_stoer (controlled extrapolation, variable order)",
   adaptive_with<ControlledStepper<BulirschStoer>>},
};
// clang-format on

const OdeintKind& kind_of(OdeintStepper stepper) {
  for (const OdeintKind& kind : kKinds)
    if (kind.stepper == stepper) return kind;
  throw std::logic_error("odeint: a stepper with no row in kKinds");
}

}  // namespace

std::unique_ptr<Integrator> odeint_method(OdeintStepper stepper, std::string name, const std::string& controller) {
  const OdeintKind& kind = kind_of(stepper);
  const std::string way = std::string("odeint's ") + kind.odeint_name;
  if (!kind.adaptive) require_controller(controller, {kConstantController}, name, way + " (no error estimate)");
  else if (!kind.fixed) require_controller(controller, {kLibraryController}, name, way + " (adaptive only)");
  else require_controller(controller, {kConstantController, kLibraryController}, name, way);
  const bool adaptive = controller == kLibraryController;
  MethodInfo info = odeint_facts(std::move(name), kind.order,
                                 adaptive ? kind.adaptive_description : kind.fixed_description, adaptive, kind.tableau);
  info.controller = controller;
  return adaptive ? kind.adaptive(std::move(info)) : kind.fixed(std::move(info));
}

}  // namespace rb

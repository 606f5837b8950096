#include "integrators/families/gsl/gsl.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>

#include "integrators/adaptive_loops.hpp"
#include "integrators/controllers/controller.hpp"
#include "integrators/driver.hpp"
#include "problems/input_error.hpp"
#include "problems/jacobian.hpp"

namespace rb {

namespace {

// What the suite knows about each GSL stepper: GSL's name and type, and its
// facts (the registry name, the family, the controller and the drive it
// asks for are added from the registry line by facts_of). The declared order is that of the solution GSL propagates
// (measured by the registry's order test); needs_jacobian: modified Newton
// (or BDF/extrapolation) with the Jacobian; variable_order: only meaningful
// with a tolerance, so adaptive only.
struct GslStepper {
  const char* name;
  const gsl_odeiv2_step_type* (*type)();
  bool variable_order;
  MethodInfo facts;
};

// clang-format off
const GslStepper kSteppers[] = {
  {"rk2", [] { return gsl_odeiv2_step_rk2; }, false,
   {.declared_order = 3, .needs_jacobian = false,
    .description = "embedded RK 2(3); GSL advances with the 3rd-order member (order 3, 3 rhs/step)"}},
  {"rk4", [] { return gsl_odeiv2_step_rk4; }, false,
   {.declared_order = 4, .needs_jacobian = false,
    .description = "classical RK4 with step doubling: each step is two RK4 half steps plus one full step for the error (11 rhs/step)"}},
  {"rkf45", [] { return gsl_odeiv2_step_rkf45; }, false,
   {.declared_order = 5, .needs_jacobian = false,
    .description = "Runge-Kutta-Fehlberg 4(5), advances with the 5th-order solution (6 rhs/step)"}},
  {"rkck", [] { return gsl_odeiv2_step_rkck; }, false,
   {.declared_order = 5, .needs_jacobian = false,
    .description = "Cash-Karp 4(5), advances with the 5th-order solution (6 rhs/step)"}},
  {"rk8pd", [] { return gsl_odeiv2_step_rk8pd; }, false,
   {.declared_order = 8, .needs_jacobian = false,
    .description = "Prince-Dormand 8(7), advances with the 8th-order solution (13 rhs/step)"}},
  {"rk1imp", [] { return gsl_odeiv2_step_rk1imp; }, false,
   {.declared_order = 1, .needs_jacobian = true,
    .description = "implicit Euler, modified Newton with the exact Jacobian, step doubling (3 solves/step)"}},
  {"rk2imp", [] { return gsl_odeiv2_step_rk2imp; }, false,
   {.declared_order = 2, .needs_jacobian = true,
    .description = "implicit midpoint (1-stage Gauss), modified Newton with the exact Jacobian, step doubling"}},
  {"rk4imp", [] { return gsl_odeiv2_step_rk4imp; }, false,
   {.declared_order = 4, .needs_jacobian = true,
    .description = "2-stage Gauss implicit RK, modified Newton with the exact Jacobian, step doubling"}},
  {"bsimp", [] { return gsl_odeiv2_step_bsimp; }, true,
   {.declared_order = 12, .needs_jacobian = true,
    .description = "Bader-Deuflhard semi-implicit extrapolation with the exact Jacobian, variable order (GSL reports 12)"}},
  {"msadams", [] { return gsl_odeiv2_step_msadams; }, true,
   {.declared_order = 12, .needs_jacobian = false,
    .description = "Adams predictor-corrector multistep (Nordsieck), variable order 1-12, functional iteration"}},
  {"msbdf", [] { return gsl_odeiv2_step_msbdf; }, true,
   {.declared_order = 5, .needs_jacobian = true,
    .description = "BDF multistep (Nordsieck), variable order 1-5, Newton with the exact Jacobian"}},
};
// clang-format on

// Newton tolerance of the fixed-step implicit steppers when none is given:
// well below the errors the order tests fit (>= 1e-12), well above rounding.
constexpr double kFixedStepNewtonTol = 1e-13;

// Per-run state the C callbacks see through gsl_odeiv2_system::params.
struct CallbackState {
  const Problem* problem = nullptr;
  // the run's cost, set by each step: every rhs call notes its validity
  // margins there (stage_flat_rhs), for the driver to look at after the step
  Cost* cost = nullptr;
  long rhs_evals = 0;
  long jacobian_evals = 0;
  std::string exception;  // what a callback caught, empty when none
};

// F(y) with the finiteness test left out, for the explicit steppers at a
// fixed step: a non-finite F makes the step's state non-finite, which the
// shared fixed-step loop checks after every step anyway (diverged, at the last
// valid state). Testing F on every call holds the return until F is done and
// cost 5 % of gsl-rk4's step (bench/perf_gsl_interface.cpp). GSL_EBADFUNC
// when the problem threw: exceptions must not cross GSL's C frames.
int rhs_callback_unchecked(double /*t*/, const double y[], double dydt[], void* params) {
  auto& s = *static_cast<CallbackState*>(params);
  ++s.rhs_evals;
  try {
    stage_flat_rhs(*s.problem, y, dydt, *s.cost);
  } catch (const std::exception& e) {
    s.exception = e.what();
    return GSL_EBADFUNC;
  }
  return GSL_SUCCESS;
}

// F(y); GSL_EBADFUNC also where F is not finite, so that GSL's adaptive and
// implicit steppers stop at once there.
int rhs_callback(double t, const double y[], double dydt[], void* params) {
  const int status = rhs_callback_unchecked(t, y, dydt, params);
  if (status != GSL_SUCCESS) return status;
  return Eigen::Map<const FlatState>(dydt).allFinite() ? GSL_SUCCESS : GSL_EBADFUNC;
}

// dfdy row-major, as GSL wants; dfdt = 0 since F does not depend on t.
int jacobian_callback(double /*t*/, const double y[], double* dfdy, double dfdt[], void* params) {
  auto& s = *static_cast<CallbackState*>(params);
  ++s.jacobian_evals;
  if (s.cost) s.cost->jacobian_columns += kFlatSize;  // its rhs-equivalents (integrators/integrator.hpp)
  FlatJacobian J;
  try {
    flat_jacobian(*s.problem, Eigen::Map<const FlatState>(y), J);
  } catch (const std::exception& e) {
    s.exception = e.what();
    return GSL_EBADFUNC;
  }
  std::copy(J.data(), J.data() + J.size(), dfdy);
  std::fill(dfdt, dfdt + kFlatSize, 0.0);
  return J.allFinite() ? GSL_SUCCESS : GSL_EBADFUNC;
}

struct DriverFree {
  void operator()(gsl_odeiv2_driver* d) const { gsl_odeiv2_driver_free(d); }
};
using DriverPtr = std::unique_ptr<gsl_odeiv2_driver, DriverFree>;

// The symbolic name of a GSL error code, for messages.
const char* gsl_code_name(int code) {
  switch (code) {
    case GSL_SUCCESS: return "GSL_SUCCESS";
    case GSL_FAILURE: return "GSL_FAILURE";
    case GSL_CONTINUE: return "GSL_CONTINUE";
    case GSL_EDOM: return "GSL_EDOM";
    case GSL_ERANGE: return "GSL_ERANGE";
    case GSL_EFAULT: return "GSL_EFAULT";
    case GSL_EINVAL: return "GSL_EINVAL";
    case GSL_EFAILED: return "GSL_EFAILED";
    case GSL_EFACTOR: return "GSL_EFACTOR";
    case GSL_ESANITY: return "GSL_ESANITY";
    case GSL_ENOMEM: return "GSL_ENOMEM";
    case GSL_EBADFUNC: return "GSL_EBADFUNC";
    case GSL_ERUNAWAY: return "GSL_ERUNAWAY";
    case GSL_EMAXITER: return "GSL_EMAXITER";
    case GSL_EZERODIV: return "GSL_EZERODIV";
    case GSL_EBADTOL: return "GSL_EBADTOL";
    case GSL_ETOL: return "GSL_ETOL";
    case GSL_EUNDRFLW: return "GSL_EUNDRFLW";
    case GSL_EOVRFLW: return "GSL_EOVRFLW";
    case GSL_ELOSS: return "GSL_ELOSS";
    case GSL_EROUND: return "GSL_EROUND";
    case GSL_ESING: return "GSL_ESING";
    case GSL_EDIVERGE: return "GSL_EDIVERGE";
    case GSL_ENOPROG: return "GSL_ENOPROG";
    case GSL_ENOPROGJ: return "GSL_ENOPROGJ";
    default: return "GSL error";
  }
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// A GSL return code as a status and a sentence. adaptive: GSL_FAILURE (and
// GSL_ENOPROG) from evolve mean it could not shrink the step any further.
Validity failure_of(int code, const CallbackState& cb, const std::string& stepper, bool adaptive, double t, double h) {
  const std::string gsl = std::string(" (") + gsl_code_name(code) + ": " + gsl_strerror(code) + ")";
  const std::string where = " at t = " + num(t) + ", h = " + num(h);
  const std::string who = "GSL " + stepper + ": ";
  if (code == GSL_EBADFUNC && !cb.exception.empty())
    return {Status::error, who + "the right-hand side threw: " + cb.exception + where + gsl};
  if (code == GSL_EBADFUNC)
    return {Status::diverged, who + "the right-hand side or its Jacobian is not finite" + where + gsl};
  if (adaptive && (code == GSL_FAILURE || code == GSL_ENOPROG))
    return {Status::step_underflow,
            who + "the step size fell below what time can resolve without meeting the tolerance" + where + gsl};
  if (code == GSL_FAILURE)
    return {Status::error, who + "the step failed (the implicit solve did not converge)" + where + gsl};
  return {Status::error, who + "the step failed" + where + gsl};
}

RunResult allocation_failure(const Problem& problem, const std::string& stepper) {
  RunResult run;
  run.status = Status::error;
  run.message = "GSL " + stepper + ": could not allocate the stepper (GSL_ENOMEM: " + gsl_strerror(GSL_ENOMEM) + ")";
  run.final_state = problem.y0();
  return run;
}

int find_stepper(const std::string& name) {
  for (std::size_t i = 0; i < std::size(kSteppers); ++i)
    if (name == kSteppers[i].name) return static_cast<int>(i);
  std::string known;
  for (const GslStepper& s : kSteppers) known += (known.empty() ? "" : ", ") + std::string(s.name);
  throw InputError("GSL has no odeiv2 stepper '" + name + "' (known: " + known + ")", "integrator");
}

}  // namespace

void gsl_errors_off() {
  // a function-local static: initialised exactly once, and thread-safe
  static const bool done = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  (void)done;
}

namespace {

// The drive a registry line's controller asks for: "constant" a fixed
// step (not for a variable-order stepper), "library" the adaptive one.
GslDrive drive_of(const GslStepper& s, const std::string& name, const std::string& controller) {
  const std::string way = std::string("GSL's ") + s.name;
  if (s.variable_order)
    require_controller(controller, {kLibraryController}, name, way + " (variable order: adaptive only)");
  else require_controller(controller, {kConstantController, kLibraryController}, name, way);
  return controller == kConstantController ? GslDrive::fixed_step : GslDrive::adaptive;
}

// The stepper's facts, called name, for the drive its controller asks for.
MethodInfo facts_of(const GslStepper& s, std::string name, const std::string& controller) {
  const bool adaptive = drive_of(s, name, controller) == GslDrive::adaptive;
  MethodInfo facts = s.facts;
  facts.name = std::move(name);
  facts.family = "gsl";
  facts.adaptive = adaptive;
  facts.controller = controller;
  facts.description = std::string("GSL odeiv2 ") + s.name + ": " + s.facts.description +
                      (adaptive ? "; adaptive (evolve + standard control on y, rtol/atol)"
                                : "; fixed step (gsl_odeiv2_step_apply per step)");
  return facts;
}

}  // namespace

GslIntegrator::GslIntegrator(const std::string& stepper, std::string name, const std::string& controller)
    : GslIntegrator(find_stepper(stepper), std::move(name), controller) {}

GslIntegrator::GslIntegrator(int index, std::string name, const std::string& controller)
    : Integrator(facts_of(kSteppers[index], std::move(name), controller)),
      index_(index),
      drive_(adaptive() ? GslDrive::adaptive : GslDrive::fixed_step) {
  gsl_errors_off();
}

namespace {

// GSL's evolve for drive_lands_itself: each call is one accepted step towards
// the bound (evolve clamps and lands itself); the attempts its control
// rejects inside the call are added to cost.rejected.
class GslEvolveStepper {
 public:
  static constexpr bool dense_output = false;
  static constexpr bool lands_itself = true;

  GslEvolveStepper(gsl_odeiv2_driver* driver, gsl_odeiv2_system* sys, CallbackState* cb, std::string stepper,
                   const FlatState& y0)
      : driver_(driver), sys_(sys), cb_(cb), stepper_(std::move(stepper)), y_(y0) {}

  // the suite's historical first step for GSL: 1e-3 of the run
  double first_step(double span) const { return 1e-3 * span; }

  void advance(double& t, double bound, double& h, Cost& cost) {
    gsl_odeiv2_evolve* evolve = driver_->e;
    cb_->cost = &cost;
    const double t_prev = t;
    const int s = gsl_odeiv2_evolve_apply(evolve, driver_->c, driver_->s, sys_, &t, bound, &h, y_.data());
    // evolve->count also counts the attempts its control rejected, so it is
    // not used; failed_steps counts every attempt thrown away, except the
    // last one of a call that fails
    const long failed = static_cast<long>(evolve->failed_steps);
    cost.rejected += failed - failed_seen_;
    failed_seen_ = failed;
    cost.rhs_evals = cb_->rhs_evals;
    cost.jacobian_evals = cb_->jacobian_evals;
    if (s != GSL_SUCCESS) {
      ++cost.rejected;
      const Validity v = failure_of(s, *cb_, stepper_, true, t_prev, h);
      throw StepFailure(v.status, v.reason);
    }
  }
  // back to y after a step the driver refused (a stage beyond a limit):
  // evolve and the stepper forget their history (a multistep method's too)
  void restore(const FlatState& y) {
    y_ = y;
    gsl_odeiv2_driver_reset(driver_);
    failed_seen_ = 0;
  }
  // evolve leaves y at no valid state on failure; the driver then ends at
  // the state it kept
  void state(FlatState& y) const { y = y_; }
  void interpolate(double, FlatState&) const {}

 private:
  gsl_odeiv2_driver* driver_;
  gsl_odeiv2_system* sys_;
  CallbackState* cb_;
  std::string stepper_;
  FlatState y_;
  long failed_seen_ = 0;
};

}  // namespace

RunResult GslIntegrator::integrate(const Problem& problem, const RunOptions& options) const {
  gsl_errors_off();
  const GslStepper& info = kSteppers[index_];
  const std::string stepper = info.name;
  CallbackState cb;
  cb.problem = &problem;
  const bool check_f = drive_ != GslDrive::fixed_step || needs_jacobian();
  gsl_odeiv2_system sys{check_f ? &rhs_callback : &rhs_callback_unchecked,
                        needs_jacobian() ? &jacobian_callback : nullptr, kFlatSize, &cb};

  if (drive_ == GslDrive::fixed_step) {
    const double h = options.h.fixed_step();
    // the implicit steppers read their Newton tolerance from the driver's
    // control (options.tolerances when given); explicit ones ignore it
    const Tolerances& given = options.tolerances;
    const double rtol = given.rtol() > 0.0 ? given.rtol() : kFixedStepNewtonTol;
    const double atol = given.atol() > 0.0 ? given.atol() : kFixedStepNewtonTol;
    const DriverPtr driver(gsl_odeiv2_driver_alloc_standard_new(&sys, info.type(), h, atol, rtol, 1.0, 0.0));
    if (!driver) return allocation_failure(problem, stepper);
    gsl_odeiv2_step* step = driver->s;
    FlatState yerr;
    // no dydt_in / dydt_out: GSL would spend an extra rhs on the latter and
    // the shared loop has no use for either
    auto advance = [&](FlatState& y, double t, double h, Cost& cost) {
      cb.cost = &cost;
      const int s = gsl_odeiv2_step_apply(step, t, h, y.data(), yerr.data(), nullptr, nullptr, &sys);
      cost.rhs_evals = cb.rhs_evals;
      cost.jacobian_evals = cb.jacobian_evals;
      if (s != GSL_SUCCESS) {
        const Validity v = failure_of(s, cb, stepper, false, t, h);
        throw StepFailure(v.status, v.reason);
      }
    };
    return drive_fixed_step(problem, options, advance);
  }

  // adaptive: validate everything before allocating (drive_lands_itself's
  // check of its options, once more: GSL allocates with them)
  const Tolerances& tol = tolerances_of(options);
  (void)output_times_of(problem, options);
  const double h0 = options.h > 0.0 ? static_cast<double>(options.h) : 1e-3 * t_end_of(problem, options);
  const DriverPtr driver(gsl_odeiv2_driver_alloc_standard_new(&sys, info.type(), h0, tol.atol(), tol.rtol(), 1.0, 0.0));
  if (!driver) return allocation_failure(problem, stepper);
  GslEvolveStepper evolve(driver.get(), &sys, &cb, stepper, problem.y0());
  return drive_lands_itself(problem, options, evolve);
}

}  // namespace rb

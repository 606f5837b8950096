#include "integrators/gsl.hpp"

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

#include "integrators/adaptive.hpp"
#include "integrators/fixed_step.hpp"
#include "problems/input_error.hpp"
#include "problems/jacobian.hpp"

namespace rb {

namespace {

// What the suite knows about each GSL stepper. order: the order of the
// solution GSL propagates (measured by the registry's order test).
struct StepperInfo {
  const char* name;
  const gsl_odeiv2_step_type* (*type)();
  int order;
  bool implicit;        // modified Newton (or BDF/extrapolation) with the Jacobian
  bool variable_order;  // only meaningful with a tolerance: adaptive only
  const char* what;     // for `rollbench list`
};

// clang-format off
const StepperInfo kSteppers[] = {
  {"rk2", [] { return gsl_odeiv2_step_rk2; }, 3, false, false,
   "embedded RK 2(3); GSL advances with the 3rd-order member (order 3, 3 rhs/step)"},
  {"rk4", [] { return gsl_odeiv2_step_rk4; }, 4, false, false,
   "classical RK4 with step doubling: each step is two RK4 half steps plus one full step for the error (11 rhs/step)"},
  {"rkf45", [] { return gsl_odeiv2_step_rkf45; }, 5, false, false,
   "Runge-Kutta-Fehlberg 4(5), advances with the 5th-order solution (6 rhs/step)"},
  {"rkck", [] { return gsl_odeiv2_step_rkck; }, 5, false, false,
   "Cash-Karp 4(5), advances with the 5th-order solution (6 rhs/step)"},
  {"rk8pd", [] { return gsl_odeiv2_step_rk8pd; }, 8, false, false,
   "Prince-Dormand 8(7), advances with the 8th-order solution (13 rhs/step)"},
  {"rk1imp", [] { return gsl_odeiv2_step_rk1imp; }, 1, true, false,
   "implicit Euler, modified Newton with the exact Jacobian, step doubling (3 solves/step)"},
  {"rk2imp", [] { return gsl_odeiv2_step_rk2imp; }, 2, true, false,
   "implicit midpoint (1-stage Gauss), modified Newton with the exact Jacobian, step doubling"},
  {"rk4imp", [] { return gsl_odeiv2_step_rk4imp; }, 4, true, false,
   "2-stage Gauss implicit RK, modified Newton with the exact Jacobian, step doubling"},
  {"bsimp", [] { return gsl_odeiv2_step_bsimp; }, 12, true, true,
   "Bader-Deuflhard semi-implicit extrapolation with the exact Jacobian, variable order (GSL reports 12)"},
  {"msadams", [] { return gsl_odeiv2_step_msadams; }, 12, false, true,
   "Adams predictor-corrector multistep (Nordsieck), variable order 1-12, functional iteration"},
  {"msbdf", [] { return gsl_odeiv2_step_msbdf; }, 5, true, true,
   "BDF multistep (Nordsieck), variable order 1-5, Newton with the exact Jacobian"},
};
// clang-format on

// Newton tolerance of the fixed-step implicit steppers when none is given:
// well below the errors the order tests fit (>= 1e-12), well above rounding.
constexpr double kFixedStepNewtonTol = 1e-13;

// Per-run state the C callbacks see through gsl_odeiv2_system::params.
struct CallbackState {
  const Problem* problem = nullptr;
  // when set, the next rhs call also fills it with the validity margins at
  // its y and clears it (see the fixed-step drive)
  ModelMargins* margins = nullptr;
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
    if (s.margins) {
      s.problem->flat_rhs(y, dydt, *s.margins);
      s.margins = nullptr;
    } else {
      s.problem->flat_rhs(y, dydt);
    }
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
Validity failure_of(int code, const CallbackState& cb, const std::string& stepper, bool adaptive, double t,
                    double h) {
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
  for (const StepperInfo& s : kSteppers) known += (known.empty() ? "" : ", ") + std::string(s.name);
  throw InputError("GSL has no odeiv2 stepper '" + name + "' (known: " + known + ")", "integrator");
}

void check_tolerance(double value, const char* key) {
  if (!(value >= 0.0) || !std::isfinite(value)) throw InputError("a tolerance must be a finite number >= 0", key);
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

GslIntegrator::GslIntegrator(const std::string& stepper, GslDrive drive)
    : index_(find_stepper(stepper)), drive_(drive) {
  gsl_errors_off();
  if (drive == GslDrive::fixed_step && kSteppers[index_].variable_order)
    throw InputError("GSL " + stepper + " has a variable order: it runs adaptive only", "integrator");
}

std::string GslIntegrator::name() const {
  return std::string("gsl-") + kSteppers[index_].name + (adaptive() ? "-adaptive" : "");
}

int GslIntegrator::declared_order() const { return kSteppers[index_].order; }

bool GslIntegrator::needs_jacobian() const { return kSteppers[index_].implicit; }

std::string GslIntegrator::description() const {
  const StepperInfo& s = kSteppers[index_];
  return std::string("GSL odeiv2 ") + s.name + ": " + s.what +
         (adaptive() ? "; adaptive (evolve + standard control on y, rtol/atol)"
                     : "; fixed step (gsl_odeiv2_step_apply per step)");
}

RunResult GslIntegrator::integrate(const Problem& problem, const RunOptions& options) const {
  gsl_errors_off();
  const StepperInfo& info = kSteppers[index_];
  const std::string stepper = info.name;
  check_tolerance(options.rtol, "rtol");
  check_tolerance(options.atol, "atol");
  CallbackState cb;
  cb.problem = &problem;
  const bool check_f = drive_ != GslDrive::fixed_step || info.implicit;
  gsl_odeiv2_system sys{check_f ? &rhs_callback : &rhs_callback_unchecked,
                        info.implicit ? &jacobian_callback : nullptr, kFlatSize, &cb};

  if (drive_ == GslDrive::fixed_step) {
    if (!(options.h > 0.0) || !std::isfinite(options.h))
      throw InputError("a fixed-step method needs a step h > 0", "h");
    // the implicit steppers read their Newton tolerance from the driver's
    // control; explicit ones ignore it
    const double rtol = options.rtol > 0.0 ? options.rtol : kFixedStepNewtonTol;
    const double atol = options.atol > 0.0 ? options.atol : kFixedStepNewtonTol;
    const DriverPtr driver(gsl_odeiv2_driver_alloc_standard_new(&sys, info.type(), options.h, atol, rtol, 1.0, 0.0));
    if (!driver) return allocation_failure(problem, stepper);
    gsl_odeiv2_step* step = driver->s;
    FlatState yerr;
    int failure = GSL_SUCCESS;
    double fail_t = 0.0, fail_h = 0.0;
    // no dydt_in / dydt_out: GSL would spend an extra rhs on the latter and
    // the shared loop has no use for either
    auto advance = [&](FlatState& y, double t, double h, Cost& cost) {
      const int s = gsl_odeiv2_step_apply(step, t, h, y.data(), yerr.data(), nullptr, nullptr, &sys);
      cost.rhs_evals = cb.rhs_evals;
      cost.jacobian_evals = cb.jacobian_evals;
      if (s != GSL_SUCCESS) {
        // the shared loop then stops on a non-finite state with the last
        // valid one; the status is replaced by the GSL failure below
        failure = s;
        fail_t = t;
        fail_h = h;
        y.setConstant(std::numeric_limits<double>::quiet_NaN());
      }
    };
    // an explicit stepper's first evaluation is at y (no dydt_in): it gives
    // the driver the validity margins there for free
    auto advance_giving_margins = [&](const FlatState& y, FlatState& next, double t, double h, Cost& cost,
                                      ModelMargins& margins) {
      next = y;
      cb.margins = &margins;
      advance(next, t, h, cost);
      cb.margins = nullptr;
    };
    RunResult run = info.implicit ? drive_fixed_step(problem, options, advance)
                                  : drive_fixed_step(problem, options, advance_giving_margins);
    if (failure != GSL_SUCCESS) {
      const Validity v = failure_of(failure, cb, stepper, false, fail_t, fail_h);
      run.status = v.status;
      run.message = v.reason;
    }
    return run;
  }

  // adaptive: validate everything before allocating
  if (options.rtol == 0.0 && options.atol == 0.0)
    throw InputError("an adaptive method needs rtol > 0 or atol > 0", "rtol");
  if (!(options.h >= 0.0) || !std::isfinite(options.h))
    throw InputError("the initial step h must be a finite number >= 0 (0 chooses it)", "h");
  const std::vector<double> outputs = output_times_of(problem, options);
  RunResult run;
  run.output.t.reserve(outputs.size());
  run.output.y.reserve(outputs.size());
  FlatState y = problem.y0();
  double t = 0.0;
  // moved out, not copied: the rows may be many
  auto stop = [&](const Validity& v, const FlatState& last_valid, double t_valid) {
    return std::move(run.stopped(v.status, v.reason, last_valid, t_valid));
  };
  // GSL's controller would accept steps at a tolerance below rounding (its
  // error estimate is noise there): refuse it up front, as odeint's adapters do
  if (const Validity v = attainable({options.rtol, options.atol}, y); v.status != Status::ok) return stop(v, y, t);
  ++run.cost.validity_checks;
  if (const Validity v = problem.check_full(y); v.status != Status::ok)
    return stop({v.status, model_stop_reason(v, t)}, y, t);
  const double h0 = options.h > 0.0 ? options.h : 1e-3 * outputs.back();
  double h = h0;
  const DriverPtr driver(
      gsl_odeiv2_driver_alloc_standard_new(&sys, info.type(), h0, options.atol, options.rtol, 1.0, 0.0));
  if (!driver) return allocation_failure(problem, stepper);
  gsl_odeiv2_evolve* evolve = driver->e;
  for (const double t_out : outputs) {
    while (t < t_out) {
      // the budget is checked between accepted steps; the rejections inside
      // one evolve_apply call (a few dozen at most) cannot be interrupted
      if (run.cost.steps + run.cost.rejected >= options.max_steps)
        return stop({Status::max_steps, "reached max_steps = " + std::to_string(options.max_steps)}, y, t);
      // evolve leaves neither y nor t at the last valid state on failure
      const FlatState y_prev = y;
      const double t_prev = t;
      const int s = gsl_odeiv2_evolve_apply(evolve, driver->c, driver->s, &sys, &t, t_out, &h, y.data());
      // a successful call is one accepted step. evolve->count also counts
      // the attempts its control rejected, so it is not used; failed_steps
      // counts every attempt thrown away, except the last one of a call
      // that fails
      run.cost.rejected = static_cast<long>(evolve->failed_steps);
      run.cost.rhs_evals = cb.rhs_evals;
      run.cost.jacobian_evals = cb.jacobian_evals;
      if (s != GSL_SUCCESS) {
        ++run.cost.rejected;
        return stop(failure_of(s, cb, stepper, true, t_prev, h), y_prev, t_prev);
      }
      ++run.cost.steps;
      // every accepted state against the model's limits, as drive_adaptive does
      ++run.cost.validity_checks;
      const Validity v = problem.check_full(y);
      if (v.status != Status::ok) return stop({v.status, model_stop_reason(v, t)}, y_prev, t_prev);
    }
    run.output.push(t, y);
  }
  run.final_state = y;
  run.stop_time = t;
  return run;
}

}  // namespace rb

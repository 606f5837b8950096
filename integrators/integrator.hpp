#pragma once
// What every integrator offers (docs/design.md): its facts (MethodInfo: a name,
// a family, a declared order, whether it adapts its step, ...), given once
// at construction, and integrate(problem, options) -> run.
//
// Integrators are immutable and stateless between runs, so one instance may
// run on many threads at once; all run state lives in integrate().
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "integrators/step_size.hpp"
#include "integrators/tolerances.hpp"
#include "problems/problem.hpp"

namespace rb {

struct ControllerKind;  // integrators/controllers/controller.hpp

// What a run is asked for, in typed values made once where the input enters
// (the CLI, a sweep): nothing downstream parses or re-checks a string or a
// tolerance (docs/design.md, "Options are typed where they enter").
struct RunOptions {
  double t_end = 0.0;     // 0 takes the problem's t_end
  StepSize h;             // step of a fixed-step method; initial step (0 = automatic) of an adaptive one
  Tolerances tolerances;  // of an adaptive method (checked on construction); none: a fixed-step run
  // Times at which the state is recorded, increasing, in (0, t_end]; t_end is
  // always recorded last. Empty: t_end only. Fixed-step methods land on them.
  std::vector<double> output_times;
  long max_steps = 100'000'000;  // accepted + rejected steps before "max-steps"
  // The step-size controller of an adaptive method whose stepper estimates
  // its error (a filter: i, pi, pid; integrators/controllers/controller.hpp),
  // looked up once by name where the name enters (filter_controller);
  // nullptr: the method's own (MethodInfo::controller). Fixed-step methods
  // and libraries' steppers keep theirs.
  const ControllerKind* controller = nullptr;
  // The call is a timed repeat: a run made in a child process (a --stepper
  // plug-in, integrators/steppers/isolated_run.hpp) integrates once untimed
  // in the child before the run it times and returns, so that its time is
  // as warm as an in-process repeat's (no first-touch copies of the
  // parent's pages in it). Every other method ignores it.
  bool warm_up = false;
};

// The facts of a method, in one place: what `rollbench list` shows, what the
// runner needs and what the report records of every run.
// Every member has a default, so that designated initializers may leave
// any out.
struct MethodInfo {
  std::string name{};    // registry name, e.g. "rkmk4"
  std::string family{};  // "rk", "rkmk", "odeint", "gsl", ...
  int declared_order = 0;
  int rotation_order = 0;  // the order in R; 0 at construction: the declared order
  int embedded_order = 0;  // the order of an adaptive method's embedded estimate; 0: none or not stated
  bool adaptive = false;
  bool needs_jacobian = false;
  std::string controller{};   // the default step-size controller: "constant", "library", "pi", ...
  std::string description{};  // one line for `rollbench list`
  // The Butcher tableau the method steps with, named where the flat view and
  // the Lie-group view both implement it (the analysis pairs methods of one
  // tableau and adaptivity, flat against Lie); empty: the method has no pair.
  std::string tableau{};
  bool on_group = false;  // R stays on SO(3) by construction (a Lie-group method)
  // The tolerance of the suite's own Newton solve of an implicit method
  // (integrators/steppers/newton.hpp): the scaled max norm of the last
  // increment; 0: the method solves nothing.
  double newton_tol = 0.0;
};

// Where the stages of the step being taken went beyond the model's limits
// (docs/design.md, "Validity at every stage"): every right-hand side a
// stepper evaluates for a step folds its margins in (Cost::note), and the
// driver turns a stage beyond a limit into a rejected step or a stop.
struct StageWatch {
  bool beyond = false;  // some stage failed Problem::within_model since the driver last looked
  ModelMargins first;   // the margins of the first such stage
  // some stage of the run came near the curvature limit
  // (ModelMargins::near_curvature_limit); never cleared
  bool near = false;
  // the largest squared contact speed |alpha'|^2 of a stage since the
  // adaptive driver last cleared it (each attempt): with the step's length
  // it estimates how far the step moved the contact point (AdaptiveRun::keep)
  double speed2 = 0.0;
};

// The cost axis in rhs-equivalents (docs/formats.md, "rhs_equivalents"):
// linear algebra is counted by its floating-point operations, at this many
// to one evaluation of F: 2 * 14^2, one forward and back substitution with
// a factored 14x14 matrix (measured at 1.4 to 2 evaluations of F; a 14x14
// LU decomposition's (2/3) 14^3 operations, 4.7 by this rate, at 4 to 5).
inline constexpr double kFlopsPerRhs = 392.0;

// Cost of a run, counted the same way by every integrator.
struct Cost {
  long steps = 0;           // accepted steps
  long rejected = 0;        // rejected steps (adaptive methods)
  long rhs_evals = 0;       // evaluations of F(y) or of (omega(z), G(z))
  long jacobian_evals = 0;  // evaluations of the 14x14 Jacobian of F
  long exp_evals = 0;       // so(3) exponentials (Lie-group methods)
  long dexpinv_evals = 0;   // dexpinv applications (Lie-group methods)
  // the suite's implicit methods (integrators/steppers/newton.hpp): Newton
  // iterations (one linear solve each; the stages they evaluate are in
  // rhs_evals, the Jacobians in jacobian_evals) and the solves that did not
  // converge (each ends its run with status error)
  long newton_iterations = 0;
  long newton_failures = 0;
  // What an implicit method pays besides F, for rhs_equivalents(): the
  // columns of its Jacobians (one AD direction each, or one evaluation of F
  // by finite differences: 14 for the flat Jacobian, 5 for dla2's), the
  // passes over the model inside its Newton iterations that are no
  // evaluations of F (dg2's energy and gradient, dla2's residual), each
  // counted as one, its LU decompositions, and the operations of its linear
  // algebra: (2/3) d^3 per decomposition of a d x d Newton matrix, 2 d^2 per
  // solve with it (one a Newton iteration), and lie-gauss's change of
  // variables. A library's own linear algebra (GSL's implicit steppers) is
  // not seen, and is not counted.
  long jacobian_columns = 0;
  long model_passes = 0;
  long lu_decompositions = 0;
  double linear_algebra_flops = 0.0;
  // evaluations whose validity margins were tested against the model's
  // limits (lift-off, curvature): every stage of every step (accepted or
  // rejected), plus the explicit checks of the start, the end and a stop
  // (docs/design.md); a starting-step guess's evaluations are not among them
  long validity_checks = 0;
  // of those, the evaluations on the paths of adaptive steps between their
  // stages (check_step_path, docs/design.md "Validity along every step")
  long path_checks = 0;
  StageWatch watch;  // not reported: the driver's view of the current step

  // The run's cost in evaluations of F: rhs_evals + jacobian_columns +
  // model_passes + linear_algebra_flops / kFlopsPerRhs. rhs_evals for an
  // explicit method; for an implicit one, what a Newton iteration costs
  // beyond its stages is in it (dla2: 1 rhs a step, 13 to 16 rhs-equivalents).
  double rhs_equivalents() const {
    return static_cast<double>(rhs_evals + jacobian_columns + model_passes) + linear_algebra_flops / kFlopsPerRhs;
  }
  // One LU decomposition of a d x d Newton matrix, counted.
  void note_decomposition(long d) {
    ++lu_decompositions;
    linear_algebra_flops += 2.0 / 3.0 * static_cast<double>(d * d * d);
  }

  // One stage's margins: counted, and kept when beyond a limit. Branch-free
  // but for the rare failure; inlined into every stage (out of line in the
  // adaptive steppers it cost 30 instructions a step). WatchNear = false
  // leaves watch.near and watch.speed2 alone: for a stepper run only by
  // drive_fixed_step, which never reads them (the test cost about 20
  // instructions a stage).
  // alpha_dot: the stage's contact velocity (alpha'), for watch.speed2;
  // nullptr for a state that is no stage.
  template <bool WatchNear = true>
  [[gnu::always_inline]] void note(const ModelMargins& m, const double* alpha_dot = nullptr) {
    ++validity_checks;
    if constexpr (WatchNear) {
      watch.near |= m.near_curvature_limit();
      if (alpha_dot) {
        const double s2 = alpha_dot[0] * alpha_dot[0] + alpha_dot[1] * alpha_dot[1];
        watch.speed2 = s2 > watch.speed2 ? s2 : watch.speed2;
      }
    }
    if (!Problem::within_model(m)) [[unlikely]] {
      if (!watch.beyond) watch.first = m;
      watch.beyond = true;
    }
  }
};

// One stage's right-hand side as every stepper evaluates it: with its
// validity margins noted in cost (the count of rhs_evals stays the
// stepper's). The margins are a few products of what the evaluation
// computes anyway.
[[gnu::always_inline]] inline void stage_flat_rhs(const Problem& problem, const double* y, double* dy, Cost& cost) {
  ModelMargins m;
  problem.flat_rhs(y, dy, m);
  cost.note(m, dy + kOffsetAlpha);
}
// The margins come back by value, so that they stay in registers.
template <bool WatchNear = true>
[[gnu::always_inline]] inline void stage_lie_rhs(const Problem& problem, const Mat3& R, const double* z, double* omega,
                                                 double* dz, Cost& cost) {
  cost.note<WatchNear>(problem.model().lie_rhs_margins(R, z, omega, dz), dz + 3);  // z = (v, alpha)
}
// The same on the model's code path General (RollingBall::has_inertia()),
// fixed at compile time by a stepper that chose it once per run.
template <bool General, bool WatchNear = true>
[[gnu::always_inline]] inline void stage_lie_rhs_on_path(const Problem& problem, const Mat3& R, const double* z,
                                                         double* omega, double* dz, Cost& cost) {
  ModelMargins m;
  problem.model().lie_rhs_on_path<General>(R, z, omega, dz, m);
  cost.note<WatchNear>(m, dz + 3);
}

// The states at the recorded output times, in order.
struct Trajectory {
  std::vector<double> t;
  std::vector<FlatState> y;
  void push(double time, const FlatState& state) {
    t.push_back(time);
    y.push_back(state);
  }
};

struct RunResult {
  Status status = Status::ok;
  std::string message;                        // why it stopped, empty when ok
  double stop_time = 0.0;                     // time of the last valid state
  FlatState final_state = FlatState::Zero();  // the last valid state
  Cost cost;
  Trajectory output;  // every output up to the stop
  // Seconds the integration took as measured where it ran, for a run made
  // in a child process (integrators/steppers/isolated_run.hpp), so that the
  // fork is not timed; NaN where the caller times the call itself.
  double solve_seconds = std::numeric_limits<double>::quiet_NaN();

  // Ends the run early: why, and the last valid state and its time.
  RunResult& stopped(Status why, const std::string& reason, const FlatState& last_valid, double t_valid) {
    status = why;
    message = reason;
    final_state = last_valid;
    stop_time = t_valid;
    return *this;
  }
};

class Integrator {
 public:
  // The facts are fixed for the integrator's life. A rotation_order of 0
  // takes the declared order; an empty controller takes "library" for an
  // adaptive method and "constant" for a fixed-step one.
  explicit Integrator(MethodInfo info) : info_(std::move(info)) {
    if (info_.rotation_order == 0) info_.rotation_order = info_.declared_order;
    if (info_.controller.empty()) info_.controller = info_.adaptive ? "library" : "constant";
  }
  virtual ~Integrator() = default;

  // All the facts as one record; the accessors below read it.
  const MethodInfo& info() const { return info_; }
  const std::string& name() const { return info_.name; }      // registry name, e.g. "rkmk4"
  const std::string& family() const { return info_.family; }  // "rk", "rkmk", "odeint", "gsl", ...
  int declared_order() const { return info_.declared_order; }
  // The order in R where a method is known to lose order in the rotation
  // only (rkmk4-seminar); the declared order elsewhere.
  int rotation_order() const { return info_.rotation_order; }
  bool adaptive() const { return info_.adaptive; }
  bool needs_jacobian() const { return info_.needs_jacobian; }
  const std::string& description() const { return info_.description; }  // one line for `rollbench list`
  // The default step-size controller (integrators/controllers/): "constant"
  // for a fixed-step method, "library" for a library's own, or a filter.
  const std::string& controller() const { return info_.controller; }

  // Advance the problem from its start to options.t_end (or the problem's),
  // recording the outputs. Never throws for a failing method: failures are
  // statuses. Throws InputError for options it cannot take (e.g. h <= 0).
  virtual RunResult integrate(const Problem& problem, const RunOptions& options) const = 0;

  // Whether integrate() forks a child process (an isolated plug-in,
  // integrators/steppers/isolated_run.hpp). A sweep makes such runs on one
  // thread with no other thread alive: a child forked from a multithreaded
  // process may block forever on a lock another thread held at the fork.
  virtual bool forks() const { return false; }

 private:
  MethodInfo info_;
};

}  // namespace rb

#pragma once
// How a run ended (docs/formats.md, report "status"). Failures are results.
#include <string_view>

namespace rb {

enum class Status {
  ok,              // reached t_end
  diverged,        // the state (or the landscape at it) is not finite
  lift_off,        // normal force F . N <= 0: the ball would leave the surface
  curvature,       // r max(kappa1, kappa2) >= 1 or E singular: no single contact
  domain,          // the contact point left the scene's domain
  step_underflow,  // an adaptive method's step fell below what time can resolve
  max_steps,       // the run hit its step budget
  crashed,         // an isolated plug-in's child process died (a signal, an exit without a result)
  timeout,         // an isolated plug-in's run passed its wall-clock limit and was killed
  off_group,       // a Lie-view plug-in returned R off SO(3): ||R^T R - I||_F > 1e-6
  chart_limit,     // a Lie step's stage left the exponential chart (|u| at dexpinv's pole)
  solver,          // an implicit method's Newton iteration did not converge (not physics: its iterates are no states)
  error,           // a library error code or exception; see the message
};

// The report's spelling: "ok", "diverged", "lift-off", ...
std::string_view status_name(Status status);

// Exit code of `rollbench trajectory`: 0 for ok, 3 for a run stopped early.
inline int exit_code_of(Status status) { return status == Status::ok ? 0 : 3; }

}  // namespace rb

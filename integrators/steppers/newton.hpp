#pragma once
// The simplified Newton iteration of the suite's implicit methods (gauss*,
// lie-gauss2*; docs/model.md, "Symmetric implicit methods"): the stage
// equations X = h Phi(X) are solved with one matrix M = I - h (A x J) per
// step, J the exact Jacobian at the step's start (problems/jacobian.hpp, by
// automatic differentiation), factored once and reused by every iteration.
// An iteration that does not converge is a run status (solver) with its
// residual, never a crash and never a physical status: its iterates are no
// states of the method, so only the stages of the iteration that converged
// are the step's stages, checked against the model's limits (lift-off,
// curvature); the driver turns the StepFailure into the stop.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/run_book.hpp"

namespace rb {

// Converged when the last increment's scaled max norm, max_i |dX_i| s_i
// (s_i = 1 / (1 + |y_i|) for a state's component, 1 for a rotation vector
// in radians), is at most this: about 45 roundings of a unit number, so
// that the symmetric methods stay symmetric to rounding (the remaining
// error is the contraction times this).
inline constexpr double kNewtonTol = 1e-14;
// Where a component's increment is large against 1 + |y_i| (a stage far
// from y_n at a large step), rounding alone may keep the increment above
// kNewtonTol: an iteration that has come below this and stops shrinking
// (it is at rounding) has converged as well.
inline constexpr double kNewtonStall = 1e-11;
// A solve that has not converged after this many iterations fails (a
// contracting simplified Newton needs 3 to 10 at the steps a benchmark
// takes).
inline constexpr int kNewtonMaxIterations = 40;

// Solves residual(X) = 0 from the X given, with lu the factored Newton
// matrix: X <- X - M^-1 residual(X). residual(X, r, first) writes the
// residual into r and evaluates (and counts) the stages it needs; first is
// true on the first iteration, where the caller may reuse the Jacobian's
// own F(y). Convergence is tested from the second iteration on, so that
// the stages have been evaluated near the solution. Every evaluation is
// counted in cost.validity_checks, but a stage beyond the model's limits
// stands (cost.watch) only where it belongs to the last iteration of a
// solve that converged (within kNewtonTol of the solution): an iterate on
// the way is no state of the method, and a diverging iteration's (a normal
// force of -3e127) says nothing of the ball. Counts the iterations in cost;
// throws StepFailure with status solver when the increment has not come
// below kNewtonTol (or stalled below kNewtonStall) after
// kNewtonMaxIterations, or is not finite after it had grown (the iteration
// diverged), with the last residual's scaled max norm in the message; an
// increment that is not finite while the iteration had not grown (at the
// first iteration: F or the Jacobian at the step's start; later: a stage of
// a contracting iteration, the step's own way) is where F stops being
// finite, status diverged as an explicit method's state there. Counts the
// failure. Each iteration's solve is counted in
// cost.linear_algebra_flops (2 d^2); the caller counts its Jacobian and
// decomposition.
template <class Residual>
void newton_solve(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& scale, Eigen::VectorXd& X,
                  Eigen::VectorXd& r, Eigen::VectorXd& dX, Residual&& residual, double t, double h, Cost& cost) {
  // the watch as the step left it before this solve (an earlier substep's stages)
  const bool beyond_before = cost.watch.beyond;
  const ModelMargins first_before = cost.watch.first;
  const double solve_flops = 2.0 * static_cast<double>(X.size()) * static_cast<double>(X.size());
  double norm = 0.0, before = 0.0;
  bool grew = false;  // some increment was larger than the one before it
  int iteration = 1;
  for (; iteration <= kNewtonMaxIterations; ++iteration) {
    cost.watch.beyond = beyond_before;  // only this iteration's stages stand
    cost.watch.first = first_before;
    residual(X, r, iteration == 1);
    dX.noalias() = lu.solve(r);
    X -= dX;
    ++cost.newton_iterations;
    cost.linear_algebra_flops += solve_flops;
    before = norm;
    norm = dX.cwiseAbs().cwiseProduct(scale).maxCoeff();
    if (!std::isfinite(norm)) break;
    grew |= iteration >= 2 && norm > before;
    if (iteration >= 2 && norm <= kNewtonTol) return;
    if (iteration >= 3 && norm <= kNewtonStall && norm >= before) return;  // at rounding
  }
  cost.watch.beyond = beyond_before;
  cost.watch.first = first_before;
  ++cost.newton_failures;
  const int done = std::min(iteration, kNewtonMaxIterations);
  char text[320];
  if (!std::isfinite(norm) && !grew) {
    // (the message as it always was)
    std::snprintf(text, sizeof text,
                  "Newton's increment is not finite at t = %.6g, h = %.6g: a stage left where F is finite", t, h);
    throw StepFailure(Status::diverged, text);
  }
  // the residual at the last iterate evaluated, in the increments' scaled max norm
  const double residual_norm = r.cwiseAbs().cwiseProduct(scale).maxCoeff();
  std::snprintf(text, sizeof text,
                "Newton did not converge at t = %.6g, h = %.6g: the residual is %.3g and the increment %.3g after "
                "%d iterations (tolerance %.3g)%s",
                t, h, residual_norm, norm, done, kNewtonTol,
                std::isfinite(norm) ? "" : "; the iteration diverged (its increment is not finite)");
  throw StepFailure(Status::solver, text);
}

}  // namespace rb

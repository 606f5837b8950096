#pragma once
// The simplified Newton iteration of the suite's implicit methods (gauss*,
// lie-gauss2*; docs/model.md, "Symmetric implicit methods"): the stage
// equations X = h Phi(X) are solved with one matrix M = I - h (A x J) per
// step, J the exact Jacobian at the step's start (problems/jacobian.hpp, by
// automatic differentiation), factored once and reused by every iteration.
// An iteration that does not converge is a run status (error) with the
// numbers, never a crash: the driver turns the StepFailure into the stop.
#include <Eigen/Dense>
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
// the stages have been evaluated (and their validity margins checked) near
// the solution. Counts the iterations in cost; throws StepFailure, status
// diverged when the increment is not finite, error when it has not come below kNewtonTol
// (or stalled below kNewtonStall) after kNewtonMaxIterations, counting the
// failure.
template <class Residual>
void newton_solve(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& scale, Eigen::VectorXd& X,
                  Eigen::VectorXd& r, Eigen::VectorXd& dX, Residual&& residual, double t, double h, Cost& cost) {
  double norm = 0.0, before = 0.0;
  for (int iteration = 1; iteration <= kNewtonMaxIterations; ++iteration) {
    residual(X, r, iteration == 1);
    dX.noalias() = lu.solve(r);
    X -= dX;
    ++cost.newton_iterations;
    before = norm;
    norm = dX.cwiseAbs().cwiseProduct(scale).maxCoeff();
    if (!std::isfinite(norm)) break;
    if (iteration >= 2 && norm <= kNewtonTol) return;
    if (iteration >= 3 && norm <= kNewtonStall && norm >= before) return;  // at rounding
  }
  ++cost.newton_failures;
  char text[256];
  std::snprintf(text, sizeof text,
                "Newton did not converge at t = %.6g, h = %.6g: the increment is %.3g after %d iterations "
                "(tolerance %.3g)",
                t, h, norm, kNewtonMaxIterations, kNewtonTol);
  if (!std::isfinite(norm)) {
    // a stage went where F is not finite: the state diverged, as an
    // explicit method's would there
    std::snprintf(text, sizeof text,
                  "Newton's increment is not finite at t = %.6g, h = %.6g: a stage left where F is finite", t, h);
    throw StepFailure(Status::diverged, text);
  }
  throw StepFailure(Status::error, text);
}

}  // namespace rb

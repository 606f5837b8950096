#include "integrators/families/discrete_gradient/discrete_gradient.hpp"

#include "integrators/controllers/controller.hpp"
#include "integrators/steppers/newton.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "problems/energy.hpp"
#include "problems/jacobian.hpp"

namespace rb {

namespace {

struct DiscreteGradientStep {
  const Problem& problem;
  FlatJacobian J;
  FlatState f;
  Eigen::MatrixXd M;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::VectorXd X, r, dX, scale;

  explicit DiscreteGradientStep(const Problem& p)
      : problem(p),
        M(kFlatSize, kFlatSize),
        lu(kFlatSize),
        X(kFlatSize),
        r(kFlatSize),
        dX(kFlatSize),
        scale(kFlatSize) {}

  void operator()(const FlatState& y, FlatState& next, double t, double h, Cost& cost) {
    constexpr int n = kFlatSize;
    flat_jacobian(problem, y, J, &f);
    ++cost.jacobian_evals;
    cost.jacobian_columns += n;
    M.setIdentity();
    M -= (0.5 * h) * J;
    lu.compute(M);
    cost.note_decomposition(n);
    const RollingBall& ball = problem.model();
    // H(y0) by an evaluation of its own each step: the last iterate's H(y1)
    // is one Newton increment off the step's end
    const double H0 = flat_energy(ball, y);
    ++cost.model_passes;
    FlatState F_m, g_m;
    X.setZero();
    scale = (1.0 + y.array().abs()).inverse().matrix();
    auto residual = [&](const Eigen::VectorXd& Z, Eigen::VectorXd& res, bool first) {
      if (first) {
        // Z = 0: ym = y1 = y0, and S(y0) grad H(y0) = F(y0), the Jacobian's own
        res = Z - h * f;
        return;
      }
      const FlatState dy = Z.head<n>();
      const FlatState y_m = y + 0.5 * dy;
      stage_flat_rhs(problem, y_m.data(), F_m.data(), cost);
      ++cost.rhs_evals;
      flat_energy(ball, y_m, &g_m);
      const double H1 = flat_energy(ball, y + dy);
      cost.model_passes += 2;  // H and its gradient at the midpoint, H at the end
      // Gonzalez: dg = g + (H1 - H0 - g . dy) dy / |dy|^2, so that dg . dy = H1 - H0
      FlatState dg = g_m;
      const double dy2 = dy.squaredNorm();
      if (dy2 > 0.0) dg += ((H1 - H0 - g_m.dot(dy)) / dy2) * dy;
      // S(ym) dg = (F (g . dg) - g (F . dg)) / |g|^2; F itself where g = 0
      // (an equilibrium: there F = 0 as well)
      const double g2 = g_m.squaredNorm();
      const FlatState S_dg = g2 > 0.0 ? FlatState((F_m * g_m.dot(dg) - g_m * F_m.dot(dg)) / g2) : F_m;
      res = Z - h * S_dg;
    };
    newton_solve(lu, scale, X, r, dX, residual, t, h, cost);
    next = y + X.head<n>();
  }
};

}  // namespace

std::unique_ptr<Integrator> discrete_gradient_method(DiscreteGradient /*gradient: gonzalez_midpoint*/, std::string name,
                                                     const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "the discrete-gradient method");
  MethodInfo info{.name = std::move(name),
                  .family = "discrete-gradient",
                  .declared_order = 2,
                  .needs_jacobian = true,
                  .controller = controller,
                  .description =
                      "discrete gradient (McLachlan-Quispel-Robidoux skew form, Gonzalez's midpoint "
                      "discrete gradient) on the flat view: energy conserved to rounding, symmetric; "
                      "simplified Newton with the AD Jacobian",
                  .newton_tol = kNewtonTol};
  return stepped_method(std::move(info), [](const Problem& problem) { return DiscreteGradientStep(problem); });
}

}  // namespace rb

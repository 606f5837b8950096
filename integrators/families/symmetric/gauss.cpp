#include "integrators/families/symmetric/gauss.hpp"

#include <string>
#include <vector>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/symmetric/composition.hpp"
#include "integrators/families/symmetric/gauss_tableaux.hpp"
#include "integrators/families/symmetric/lie_midpoint.hpp"
#include "integrators/steppers/newton.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "problems/input_error.hpp"
#include "problems/jacobian.hpp"

namespace rb {

namespace {

using methods::ImplicitTableau;

// One collocation step on the flat view. The unknowns are the stage
// increments Z_i = Y_i - y_n (14 s numbers) with Z_i = h sum_j a_ij F(y_n +
// Z_j); the update y_{n+1} = y_n + sum_i d_i Z_i, d = A^-T b, needs no
// further evaluation (Hairer & Wanner, Solving ODEs II, IV.8).
struct GaussStep {
  const Problem& problem;
  const ImplicitTableau& tableau;
  Eigen::VectorXd d;  // the update's weights on Z
  FlatJacobian J;
  FlatState f;
  std::vector<FlatState> K;  // F at the stages
  Eigen::MatrixXd M;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::VectorXd X, r, dX, scale;

  GaussStep(const Problem& p, const ImplicitTableau& t) : problem(p), tableau(t), K(t.stages) {
    const int s = t.stages, n = s * kFlatSize;
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> A(t.a.data(), s, s);
    d = A.transpose().partialPivLu().solve(Eigen::Map<const Eigen::VectorXd>(t.b.data(), s));
    M.resize(n, n);
    lu = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
    X.resize(n);
    r.resize(n);
    dX.resize(n);
    scale.resize(n);
  }

  void operator()(const FlatState& y, FlatState& next, double t, double h, Cost& cost) {
    const int s = tableau.stages;
    constexpr int n = kFlatSize;
    flat_jacobian(problem, y, J, &f);
    ++cost.jacobian_evals;
    cost.jacobian_columns += n;
    M.setIdentity();
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) M.block<n, n>(i * n, j * n) -= (h * tableau.a[i * s + j]) * J;
    lu.compute(M);
    cost.note_decomposition(s * n);
    X.setZero();
    for (int i = 0; i < s; ++i) scale.segment<n>(i * n) = (1.0 + y.array().abs()).inverse().matrix();
    auto residual = [&](const Eigen::VectorXd& Z, Eigen::VectorXd& res, bool first) {
      for (int j = 0; j < s; ++j) {
        if (first) {
          K[j] = f;  // every stage is at y_n while Z = 0: the Jacobian's own F(y_n)
        } else {
          const FlatState Y = y + Z.segment<n>(j * n);
          stage_flat_rhs(problem, Y.data(), K[j].data(), cost);
          ++cost.rhs_evals;
        }
      }
      for (int i = 0; i < s; ++i) {
        res.segment<n>(i * n) = Z.segment<n>(i * n);
        for (int j = 0; j < s; ++j) res.segment<n>(i * n) -= (h * tableau.a[i * s + j]) * K[j];
      }
    };
    newton_solve(lu, scale, X, r, dX, residual, t, h, cost);
    next = y;
    for (int i = 0; i < s; ++i) next += d[i] * X.segment<n>(i * n);
  }
};

// (the controller: "constant", checked by the caller)
MethodInfo implicit_facts(std::string name, std::string family, int order, std::string description, std::string tableau,
                          bool on_group, const std::string& controller) {
  return {.name = std::move(name),
          .family = std::move(family),
          .declared_order = order,
          .needs_jacobian = true,
          .controller = controller,
          .description = std::move(description),
          .tableau = std::move(tableau),
          .on_group = on_group,
          .newton_tol = kNewtonTol};
}

// "" for order 2, "-tj4" / "-tj6" for the compositions (the suffix of the
// tableau name the flat and the Lie method share); InputError for an order
// the triple jump does not give.
std::string composition_suffix(const std::string& name, int order) {
  if (order != 2 && order != 4 && order != 6)
    throw InputError(
        "'" + name + "': the midpoint rule is composed to order 2, 4 or 6 here, not " + std::to_string(order),
        "integrator");
  return order == 2 ? "" : "-tj" + std::to_string(order);
}

// How a composition is described: nothing for order 2.
std::string composed_how(int order) {
  return order == 2 ? std::string()
                    : ", composed by the triple jump to order " + std::to_string(order) + " (" +
                          std::to_string(methods::triple_jump(order).size()) + " substeps)";
}

}  // namespace

std::unique_ptr<Integrator> gauss_method(int stages, std::string name, const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "Gauss collocation");
  if (stages < 1 || stages > 3)
    throw InputError("'" + name + "': Gauss collocation has 1, 2 or 3 stages here, not " + std::to_string(stages),
                     "integrator");
  ImplicitTableau tableau = methods::gauss(stages);
  // gauss2 is also the base of the compositions, whose Lie twins exist;
  // gauss4 and gauss6 have none
  std::string twin = stages == 1 ? tableau.name : std::string();
  MethodInfo info = implicit_facts(std::move(name), "gauss", tableau.order,
                                   "Gauss-Legendre collocation, " + std::to_string(stages) +
                                       (stages == 1 ? " stage (the implicit midpoint rule)" : " stages") +
                                       ", on the flat view; simplified Newton with the AD Jacobian",
                                   twin, false, controller);
  return stepped_method(std::move(info),
                        [tableau = std::move(tableau)](const Problem& problem) { return GaussStep(problem, tableau); });
}

std::unique_ptr<Integrator> midpoint_composition(int order, std::string name, const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "the composed implicit midpoint rule");
  if (order == 2) return gauss_method(1, std::move(name), controller);
  const std::string tableau = "gauss2" + composition_suffix(name, order);
  MethodInfo info = implicit_facts(std::move(name), "gauss", order,
                                   "the implicit midpoint rule (gauss2) on the flat view" + composed_how(order) +
                                       "; simplified Newton with the AD Jacobian",
                                   tableau, false, controller);
  return stepped_method(std::move(info),
                        [gauss2 = methods::gauss(1), gammas = methods::triple_jump(order)](const Problem& problem) {
                          return Composed<GaussStep>{GaussStep(problem, gauss2), &gammas, {}};
                        });
}

std::unique_ptr<Integrator> lie_midpoint_composition(int order, std::string name, const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "the Lie midpoint rule");
  const std::string tableau = "gauss2" + composition_suffix(name, order);
  MethodInfo info =
      implicit_facts(std::move(name), "lie-gauss", order,
                     "the Lie midpoint rule theta = h xi(exp(theta/2) y0), y1 = exp(theta) y0, on the Lie-group view" +
                         composed_how(order) + "; simplified Newton with the AD Jacobian",
                     tableau, true, controller);
  return stepped_method(std::move(info), [gammas = methods::triple_jump(order)](const Problem& problem) {
    return Composed<LieMidpointStep>{LieMidpointStep(problem), &gammas, {}};
  });
}

}  // namespace rb

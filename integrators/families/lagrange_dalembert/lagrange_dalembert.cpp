#include "integrators/families/lagrange_dalembert/lagrange_dalembert.hpp"

#include <unsupported/Eigen/AutoDiff>

#include "integrators/controllers/controller.hpp"
#include "integrators/steppers/newton.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "problems/cayley.hpp"

namespace rb {

namespace {

constexpr int kUnknowns = 5;  // phi (body rotation vector, 3) and the contact's step dalpha (2)
using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, kUnknowns, 1>>;

// Where the ball touches at alpha = (x, y): the normal N, the centre C =
// (x, y, f) + r N and its derivative C' (3x2), in scalars S (double or Ad).
template <class S>
struct Contact {
  Eigen::Matrix<S, 3, 1> N, C;
  Eigen::Matrix<S, 3, 2> C_d;
};

// The landscape's geometry from the model's own kinematics (at v = 0, so
// that nothing but the geometry is computed), and the height.
template <class S>
Contact<S> contact_at(const RollingBall& ball, const S& x, const S& y) {
  const S z[kZSize] = {S(0.0), S(0.0), S(0.0), x, y};
  const Kinematics<S> k = ball.kinematics<false>(Mat3::Identity().eval(), z);
  S f;
  if constexpr (std::is_same_v<S, double>) f = ball.landscape().height(x, y);
  else f = ball.landscape().at(x, y).f;
  Contact<S> c;
  c.N = k.N;
  c.C = Eigen::Matrix<S, 3, 1>(x, y, f) + S(ball.params().radius) * k.N;
  c.C_d = k.C_d;
  return c;
}

template <class S>
Eigen::Matrix<S, 3, 1> cast3(const Vec3& a) {
  return Eigen::Matrix<S, 3, 1>(S(a[0]), S(a[1]), S(a[2]));
}

struct LagrangeDalembertStep {
  const Problem& problem;
  const RollingBall& ball;
  double m, r, g0;
  Vec3 theta_body;  // principal moments about the centre (the homogeneous ball's 2/5 m r^2)
  Eigen::MatrixXd M;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::VectorXd X, res, dX, scale, res0;
  // the last step's end and its rates (its stage): the next step's predictor
  FlatState cached_y;
  Vec3 cached_omega;
  ZState cached_dz;
  bool cached = false;

  explicit LagrangeDalembertStep(const Problem& p)
      : problem(p),
        ball(p.model()),
        m(p.model().params().mass),
        r(p.model().params().radius),
        g0(p.model().params().gravity),
        theta_body(p.model().params().inertia.value_or(Vec3::Constant(0.4 * m * r * r))),
        M(kUnknowns, kUnknowns),
        lu(kUnknowns),
        X(kUnknowns),
        res(kUnknowns),
        dX(kUnknowns),
        scale(kUnknowns),
        res0(kUnknowns) {}

  // The step's five equations at X = (phi, dalpha), from (R0, v0, alpha0)
  // and the start's geometry c0 (docs/model.md): the momentum at the start
  // over m r^2, and the trapezoidal rolling constraint over r.
  template <class S>
  void residual(const S* x, S* out, const Mat3& R0, const Vec3& v0, const Vec2& alpha0, const Contact<double>& c0,
                double h) const {
    using V3 = Eigen::Matrix<S, 3, 1>;
    const V3 phi(x[0], x[1], x[2]);
    const S x1 = alpha0[0] + x[3], y1 = alpha0[1] + x[4];
    const Contact<S> c1 = contact_at<S>(ball, x1, y1);
    const V3 N0 = cast3<S>(c0.N);
    const V3 dC = c1.C - cast3<S>(c0.C);
    // R0 dcayinv_{-phi}(Theta phi), with dcayinv_{-u}(w) = w + u x w / 2 + (u . w) u / 4
    const V3 w = cast3<S>(theta_body).cwiseProduct(phi);
    const V3 d = w + S(0.5) * phi.cross(w) + S(0.25) * phi.dot(w) * phi;
    V3 Rd, theta;
    for (int i = 0; i < 3; ++i) {
      Rd[i] = R0(i, 0) * d[0] + R0(i, 1) * d[1] + R0(i, 2) * d[2];
      theta[i] = R0(i, 0) * phi[0] + R0(i, 1) * phi[1] + R0(i, 2) * phi[2];
    }
    // N x g with g = (0, 0, -g0)
    const V3 N0_g(-g0 * N0[1], g0 * N0[0], S(0.0));
    const V3 A = Rd + S(m * r) * N0.cross(dC) - S(0.5 * h * h * m * r) * N0_g - S(h) * cast3<S>(v0);
    const V3 slip0 = dC - S(r) * theta.cross(N0), slip1 = dC - S(r) * theta.cross(c1.N);
    const Eigen::Matrix<S, 2, 1> B = c0.C_d.cast<S>().transpose() * slip0 + c1.C_d.transpose() * slip1;
    const double mr2 = m * r * r;
    for (int i = 0; i < 3; ++i) out[i] = A[i] / mr2;
    for (int i = 0; i < 2; ++i) out[3 + i] = B[i] / r;
  }

  void operator()(const FlatState& y, FlatState& next, double t, double h, Cost& cost) {
    const Mat3 R0 = rotation_of(y);
    const Vec3 v0 = momentum_of(y);
    const Vec2 alpha0 = contact_of(y);
    const ZState z0 = z_of(y);
    // the predictor's rates at the start: the last step's stage where it
    // ended here (an evaluation of its own only at a run's first step)
    if (!cached || cached_y != y) {
      problem.lie_rhs(R0, z0.data(), cached_omega.data(), cached_dz.data());
    }
    const Contact<double> c0 = contact_at(ball, alpha0[0], alpha0[1]);
    // an explicit predictor: the rotation and the contact's move at the start's rates
    X.head<3>() = h * (R0.transpose() * cached_omega);
    X.tail<2>() = h * cached_dz.tail<2>();
    // the Newton matrix: the residual's Jacobian at the predictor, by AD
    Ad xa[kUnknowns], ra[kUnknowns];
    for (int j = 0; j < kUnknowns; ++j) xa[j] = Ad(X[j], kUnknowns, j);
    residual<Ad>(xa, ra, R0, v0, alpha0, c0, h);
    for (int i = 0; i < kUnknowns; ++i) {
      M.row(i) = ra[i].derivatives().transpose();
      res0[i] = ra[i].value();
    }
    ++cost.jacobian_evals;
    cost.jacobian_columns += kUnknowns;  // the AD pass carries five directions
    ++cost.model_passes;                 // the start's geometry
    lu.compute(M);
    cost.note_decomposition(kUnknowns);
    scale.head<3>().setOnes();  // phi in radians
    scale.tail<2>() = (1.0 + alpha0.array().abs()).inverse().matrix();
    auto equations = [&](const Eigen::VectorXd& x, Eigen::VectorXd& out, bool first) {
      if (first) {
        out = res0;  // the AD pass's values at the predictor
        return;
      }
      residual<double>(x.data(), out.data(), R0, v0, alpha0, c0, h);
      ++cost.model_passes;  // the landscape's geometry at alpha1
    };
    newton_solve(lu, scale, X, res, dX, equations, t, h, cost);

    const Vec3 phi = X.head<3>();
    const Vec2 alpha1 = alpha0 + X.tail<2>();
    const Contact<double> c1 = contact_at(ball, alpha1[0], alpha1[1]);
    ++cost.model_passes;
    const Vec3 dC = c1.C - c0.C, N_sum = c0.N + c1.N;
    const Vec3 v1 =
        v0 + (m * r / h) * (c1.N - c0.N).cross(dC) + (0.5 * h * m * r) * Vec3(-g0 * N_sum[1], g0 * N_sum[0], 0.0);
    const Mat3 R1 = R0 * so3_cay(phi);
    ++cost.exp_evals;
    next = make_flat(R1, v1, alpha1);
    // the step's stage: its end, checked against the model's limits; its
    // rates are the next step's predictor
    const ZState z1 = z_of(next);
    stage_lie_rhs(problem, R1, z1.data(), cached_omega.data(), cached_dz.data(), cost);
    ++cost.rhs_evals;
    cached_y = next;
    cached = true;
  }
};

}  // namespace

std::unique_ptr<Integrator> lagrange_dalembert_method(DiscreteConstraint /*constraint: trapezoidal*/, std::string name,
                                                      const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "the discrete Lagrange-d'Alembert method");
  MethodInfo info{.name = std::move(name),
                  .family = "nonholonomic-variational",
                  .declared_order = 2,
                  .needs_jacobian = true,
                  .controller = controller,
                  .description =
                      "discrete Lagrange-d'Alembert on SO(3) x R^2 (nodal variations in the rolling distribution, "
                      "trapezoidal discrete constraint; McLachlan-Perlmutter 2006): symmetric, R by Cayley steps; "
                      "simplified Newton with the AD Jacobian of its residual",
                  .on_group = true,
                  .newton_tol = kNewtonTol};
  return stepped_method(std::move(info), [](const Problem& problem) { return LagrangeDalembertStep(problem); });
}

}  // namespace rb

#include "integrators/families/baselines/baselines.hpp"

#include "integrators/controllers/controller.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

// One classical RK4 step on any fixed-size state x' = f(x).
template <class State, class F>
void rk4_step(State& x, double h, F&& f) {
  State k1, k2, k3, k4;
  f(x, k1);
  f(State(x + (0.5 * h) * k1), k2);
  f(State(x + (0.5 * h) * k2), k3);
  f(State(x + h * k3), k4);
  x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

// (q, z): the unit quaternion (w, x, y, z) of R and z = (v, alpha).
using QuatState = Eigen::Matrix<double, 4 + kZSize, 1>;

Mat3 rotation_of_quaternion(const Eigen::Vector4d& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
}

// R pulled back onto SO(3) after each RK4 step of the flat view
struct ProjectedStep {
  const Problem& problem;
  RotationFix fix;  // project_newton_schulz or project_svd
  void operator()(FlatState& y, double /*t*/, double h, Cost& cost) const {
    rk4_step(y, h, [&](const FlatState& x, FlatState& dx) { stage_flat_rhs(problem, x.data(), dx.data(), cost); });
    cost.rhs_evals += 4;
    // a non-finite R has no closest rotation; the driver reports it diverged
    if (!y.allFinite()) return;
    const Mat3 R = rotation_of(y);
    set_rotation(y, fix == RotationFix::project_svd ? project_to_so3(R) : project_to_so3_newton_schulz(R));
  }
};

// RK4 on (q, z). q lives across steps: drive_fixed_step always passes back
// the state the last step returned (a run stops at the first invalid one),
// so R(q) in y and q agree
struct QuaternionStep {
  const Problem& problem;
  bool anisotropic;
  QuatState x;

  explicit QuaternionStep(const Problem& p) : problem(p), anisotropic(p.model().anisotropic()) {
    const Eigen::Quaterniond q0(rotation_of(p.y0()));
    x << q0.w(), q0.x(), q0.y(), q0.z(), z_of(p.y0());
  }

  void f(const QuatState& s, QuatState& ds, Cost& cost) const {
    Vec3 omega;
    ZState g;
    const ZState z = s.tail<kZSize>();
    // R enters only for an anisotropic ball: then the stage's own q
    const Mat3 R = anisotropic ? rotation_of_quaternion(s.head<4>().normalized()) : Mat3::Identity();
    stage_lie_rhs(problem, R, z.data(), omega.data(), g.data(), cost);
    // (0, omega) (x) q = (-omega . q_v, q_w omega + omega x q_v)
    const Vec3 qv = s.segment<3>(1);
    ds[0] = -0.5 * omega.dot(qv);
    ds.segment<3>(1) = 0.5 * (s[0] * omega + omega.cross(qv));
    ds.tail<kZSize>() = g;
  }

  void operator()(FlatState& y, double /*t*/, double h, Cost& cost) {
    x.tail<kZSize>() = z_of(y);
    rk4_step(x, h, [&](const QuatState& s, QuatState& ds) { f(s, ds, cost); });
    cost.rhs_evals += 4;
    x.head<4>().normalize();
    set_rotation(y, rotation_of_quaternion(x.head<4>()));
    y.tail<kZSize>() = x.tail<kZSize>();
  }
};

}  // namespace

std::unique_ptr<Integrator> rk4_baseline(RotationFix fix, std::string name, const std::string& controller) {
  require_controller(controller, {kConstantController}, name, "a fixed-step baseline");
  if (fix == RotationFix::unit_quaternion) {
    MethodInfo info{.name = std::move(name),
                    .family = "quaternion",
                    .declared_order = 4,
                    .controller = controller,
                    .description =
                        "classical RK4 on (q, z), a unit quaternion for R with q' = (0, omega) (x) q / 2, "
                        "normalised after every step: 4 rhs and one normalisation a step"};
    return stepped_method(std::move(info), [](const Problem& problem) { return QuaternionStep(problem); });
  }
  MethodInfo info{.name = std::move(name),
                  .family = "projection",
                  .declared_order = 4,
                  .controller = controller,
                  .description = fix == RotationFix::project_svd
                                     ? "classical RK4 on the flat view with R projected onto SO(3) after every "
                                       "step (polar factor by a 3x3 SVD): 4 rhs and one SVD a step"
                                     : "classical RK4 on the flat view with R projected onto SO(3) after every "
                                       "step (polar factor by a Newton-Schulz step): 4 rhs and two 3x3 products "
                                       "a step",
                  .tableau = "rk4"};
  return stepped_method(std::move(info), [fix](const Problem& problem) { return ProjectedStep{problem, fix}; });
}

}  // namespace rb

#include "integrators/families/exp_product/exp_product_adaptive.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/exp_product/exp_product_stages.hpp"
#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"

namespace rb {

namespace {

// The pair's steps for drive_estimating (integrators/adaptive_loops.hpp), on the
// shared try/accept skeleton: an error norm for the controller, which
// decides.
class ExpPairStepper : public EmbeddedPair<ExpPairStepper> {
 public:
  static constexpr bool dense_output = false;

  ExpPairStepper(const Problem& problem, const ExpPlan& plan, int error_order, const Tolerances& tol)
      : problem_(&problem),
        step_{problem, plan, problem.model().anisotropic(), K_, L_, Rs_},
        error_order_(error_order),
        tol_(tol),
        R_(rotation_of(problem.y0())),
        z_(z_of(problem.y0())) {}

  int error_order() const { return error_order_; }

  void first_stage(Cost& cost) {
    stage_lie_rhs(*problem_, R_, z_.data(), K_[0].data(), L_[0].data(), cost);
    ++cost.rhs_evals;
  }

  // the step kept in R_new_, dz_new_ for commit
  double attempt(double h, Cost& cost) {
    step_.later_stages(R_, z_, h, cost);
    R_new_ = step_.apply(step_.plan.update, R_, h, cost);
    const Mat3 R_low = step_.apply(step_.plan.embedded, R_, h, cost);
    step_.plan.z_update.sum(dz_new_, h, L_);
    ZState dz_low;
    step_.plan.z_embedded.sum(dz_low, h, L_);
    finite_ = R_new_.allFinite() && dz_new_.allFinite() && R_low.allFinite() && dz_low.allFinite();
    if (!finite_) return std::numeric_limits<double>::quiet_NaN();
    // vee of the skew part of R_high R_low^T
    const Mat3 D = R_new_ * R_low.transpose();
    const Vec3 e_rot(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
    const double rotation = (0.5 * e_rot / rotation_scale(tol_)).squaredNorm();
    return rms_error(rotation + scaled_squares(ZState(dz_new_ - dz_low), value_scale(tol_, z_, ZState(z_ + dz_new_))),
                     3 + kZSize);
  }
  bool tried_finite() const { return finite_; }

  // the next attempt starts at the new state
  bool commit(double /*t*/, double /*h*/, Cost& /*cost*/) {
    R_ = R_new_;
    z_ += dz_new_;
    return false;
  }

  void state(FlatState& y) const {
    set_rotation(y, R_);
    y.tail<kZSize>() = z_;
  }
  void interpolate(double, FlatState& y) const { state(y); }
  // state() wrote y from R_ and z_, so they come back bit for bit
  void go_back(const FlatState& y) {
    R_ = rotation_of(y);
    z_ = z_of(y);
  }

 private:
  const Problem* problem_;
  std::array<Vec3, kMaxStages> K_;
  std::array<ZState, kMaxStages> L_;
  std::array<Mat3, kMaxStages> Rs_;
  ExpProductStep step_;
  int error_order_;
  Tolerances tol_;
  Mat3 R_, R_new_;
  ZState z_, dz_new_;
  bool finite_ = false;  // the step tried last is finite
};

}  // namespace

std::unique_ptr<Integrator> exp_product_adaptive(ExpProductScheme scheme, const std::string& controller) {
  (void)filter_controller(controller);  // throws for an unknown one
  if (scheme.embedded_order < 1 || plan_of(scheme).embedded.count == 0)
    throw std::invalid_argument(scheme.name + ": an adaptive method needs an embedded update and its order");
  const ExpPlan plan = plan_of(scheme);
  int stage_exps = 0;
  for (std::size_t i = 1; i < static_cast<std::size_t>(plan.stages); ++i) stage_exps += plan.stage[i].count;
  const int update_exps = plan.update.count + plan.embedded.count;
  MethodInfo info{.name = scheme.name,
                  .family = scheme.family + "-adaptive",
                  .declared_order = scheme.order,
                  .embedded_order = scheme.embedded_order,
                  .controller = controller,
                  .description = "adaptive " + scheme.kind + " method, order " + std::to_string(scheme.order) +
                                 " with an embedded order-" + std::to_string(scheme.embedded_order) +
                                 " update (error on (rotation vector, z), " + controller_title(controller) +
                                 " controller): " + std::to_string(plan.stages - 1) + " rhs and " +
                                 std::to_string(stage_exps + update_exps) + " exponentials an attempt (" +
                                 std::to_string(update_exps) +
                                 " for a homogeneous ball); steps clamped onto the outputs: " + scheme.source,
                  .on_group = true};
  const int error_order = std::min(scheme.order, scheme.embedded_order) + 1;
  return adaptive_method(std::move(info), [plan, error_order](const Problem& problem, const RunOptions&,
                                                              const Tolerances& tol, auto&& drive) {
    ExpPairStepper stepper(problem, plan, error_order, tol);
    return drive(stepper);
  });
}

}  // namespace rb

#include "integrators/steppers/flat_embedded.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

// The pair's steps for drive_adaptive (integrators/driver.hpp): an error
// norm for the controller, which decides.
class FlatPairStepper {
 public:
  static constexpr bool dense_output = false;

  FlatPairStepper(const Problem& problem, const Tableau& tableau, const Tolerances& tol)
      : problem_(&problem),
        tableau_(&tableau),
        tol_(tol),
        y_(problem.y0()),
        attempt_(tableau.attempt_stages()),
        fsal_in_attempt_(tableau.fsal_in_attempt()) {}

  int error_order() const { return tableau_->error_order(); }

  // The error norm of a step of h (NaN when the step is not finite); the
  // step is kept in y_new_ for accept.
  double try_step(double /*t*/, double h, Cost& cost) {
    if (!have_first_) {
      stage_flat_rhs(*problem_, y_.data(), k_[0].data(), cost);
      ++cost.rhs_evals;
      have_first_ = true;
    }
    // the attempt's stages; the FSAL stage (if among them) is at y_new
    // itself, whose sum y + h sum b_j k_j is the same sum as its row's
    for (int i = 1; i < attempt_; ++i) {
      stage_ = y_ + h * combine(row(i), i);
      stage_flat_rhs(*problem_, stage_.data(), k_[static_cast<std::size_t>(i)].data(), cost);
      ++cost.rhs_evals;
    }
    y_new_ = y_ + h * combine(tableau_->b_weights().data(), attempt_);
    return y_new_.allFinite() ? error_norm(h) : std::numeric_limits<double>::quiet_NaN();
  }

  void accept(double /*t*/, double /*h*/, Cost& /*cost*/) {
    y_ = y_new_;
    // the next step's first stage: the FSAL stage, or evaluated by the next
    // attempt (so that its margins are that attempt's)
    if (fsal_in_attempt_) k_[0] = k_[static_cast<std::size_t>(*tableau_->fsal_stage())];
    else have_first_ = false;
  }

  void state(FlatState& y) const { y = y_; }
  void interpolate(double, FlatState& y) const { y = y_; }
  // back to y, the state before the step the driver refused after
  // accepting it (its path went beyond a limit); the first stage there is
  // evaluated again by the next attempt
  void restore(const FlatState& y) {
    y_ = y;
    have_first_ = false;
  }

 private:
  // sum_j w_j k_j over the first count stages
  FlatState combine(const double* w, int count) const {
    FlatState sum = FlatState::Zero();
    for (int j = 0; j < count; ++j)
      if (w[j] != 0.0) sum += w[j] * k_[static_cast<std::size_t>(j)];
    return sum;
  }

  const double* row(int i) const {
    return &tableau_->a_row_major()[static_cast<std::size_t>(i * tableau_->total_stages())];
  }

  double error_norm(double h) const {
    const FlatState scale = (tol_.atol() + tol_.rtol() * y_.cwiseAbs().cwiseMax(y_new_.cwiseAbs()).array()).matrix();
    const FlatState e = h * combine(tableau_->e().data(), attempt_);
    return std::sqrt((e.array() / scale.array()).square().sum() / static_cast<double>(kFlatSize));
  }

  const Problem* problem_;
  const Tableau* tableau_;
  Tolerances tol_;
  FlatState y_, y_new_, stage_;
  int attempt_;  // the stages of an attempt
  bool fsal_in_attempt_;
  std::array<FlatState, kMaxStages> k_;
  bool have_first_ = false;
};

}  // namespace

std::unique_ptr<Integrator> rk_adaptive(Tableau tableau, std::string name, const std::string& controller) {
  require_embedded_pair(tableau, controller);
  const Tableau& t = tableau;
  // the flat error norm is the plain one
  if (!t.e_stretched().empty())
    throw InputError("tableau '" + t.name() + "' has a stretched error estimate, which the flat pair does not combine",
                     "e_stretched");
  MethodInfo info{.name = std::move(name),
                  .family = "rk-adaptive",
                  .declared_order = t.order(),
                  .embedded_order = t.embedded_order(),
                  .controller = controller,
                  .description = "adaptive explicit RK on the " + t.name() + " pair (order " +
                                 std::to_string(t.order()) + ", " + std::to_string(t.attempt_stages()) + " stages" +
                                 (t.fsal_in_attempt() ? ", FSAL" : "") + ", " + controller_title(controller) +
                                 " controller by default) on the flat view; steps clamped onto the outputs",
                  .tableau = t.name()};
  return adaptive_method(std::move(info), [tableau = std::move(tableau)](const Problem& problem, const RunOptions&,
                                                                         const Tolerances& tol, auto&& drive) {
    FlatPairStepper stepper(problem, tableau, tol);
    return drive(stepper);
  });
}

}  // namespace rb

#include "integrators/families/rk/flat_embedded.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "integrators/stage_terms.hpp"
#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

// The pair's steps for drive_estimating (integrators/adaptive_loops.hpp), on the
// shared try/accept skeleton: an error norm for the controller, which
// decides.
class FlatPairStepper : public EmbeddedPair<FlatPairStepper> {
 public:
  static constexpr bool dense_output = false;

  FlatPairStepper(const Problem& problem, const Tableau& tableau, const Tolerances& tol)
      : problem_(&problem),
        tableau_(&tableau),
        tol_(tol),
        y_(problem.y0()),
        attempt_(tableau.attempt_stages()),
        fsal_in_attempt_(tableau.fsal_in_attempt()),
        b_(tableau.b_weights().data(), attempt_),
        e_(tableau.e().data(), attempt_) {
    for (int i = 1; i < attempt_; ++i)
      rows_[static_cast<std::size_t>(i)] =
          StageTerms::Row(&tableau.a_row_major()[static_cast<std::size_t>(i * tableau.total_stages())], i);
  }

  int error_order() const { return tableau_->error_order(); }

  void first_stage(Cost& cost) {
    stage_flat_rhs(*problem_, y_.data(), k_[0].data(), cost);
    ++cost.rhs_evals;
  }

  // the attempt's stages; the FSAL stage (if among them) is at y_new
  // itself, whose sum y + h sum b_j k_j is the same sum as its row's
  double attempt(double h, Cost& cost) {
    for (int i = 1; i < attempt_; ++i) {
      stage_ = y_ + h * rows_[static_cast<std::size_t>(i)].combination<FlatState>(k_);
      stage_flat_rhs(*problem_, stage_.data(), k_[static_cast<std::size_t>(i)].data(), cost);
      ++cost.rhs_evals;
    }
    y_new_ = y_ + h * b_.combination<FlatState>(k_);
    return error_norm(h);
  }
  bool tried_finite() const { return y_new_.allFinite(); }

  // the next step's first stage: the FSAL stage, or evaluated by the next
  // attempt (so that its margins are that attempt's)
  bool commit(double /*t*/, double /*h*/, Cost& /*cost*/) {
    y_ = y_new_;
    if (!fsal_in_attempt_) return false;
    k_[0] = k_[static_cast<std::size_t>(*tableau_->fsal_stage())];
    return true;
  }

  void state(FlatState& y) const { y = y_; }
  void interpolate(double, FlatState& y) const { y = y_; }
  void go_back(const FlatState& y) { y_ = y; }

 private:
  double error_norm(double h) const {
    const FlatState e = h * e_.combination<FlatState>(k_);
    return rms_error(scaled_squares(e, value_scale(tol_, y_, y_new_)), kFlatSize);
  }

  const Problem* problem_;
  const Tableau* tableau_;
  Tolerances tol_;
  FlatState y_, y_new_, stage_;
  int attempt_;  // the stages of an attempt
  bool fsal_in_attempt_;
  std::array<StageTerms::Row, kMaxStages> rows_;  // a's rows of the attempt's stages
  StageTerms::Row b_, e_;
  std::array<FlatState, kMaxStages> k_;
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

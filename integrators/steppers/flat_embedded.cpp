#include "integrators/steppers/flat_embedded.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "integrators/adaptive.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

// The pair's steps for drive_adaptive (integrators/driver.hpp): an error
// norm for the controller, which decides.
class FlatPairStepper {
 public:
  static constexpr bool dense_output = false;

  FlatPairStepper(const Problem& problem, const EmbeddedPair& pair, const Tolerances& tol)
      : problem_(&problem), pair_(&pair), tol_(tol), y_(problem.y0()) {}

  int error_order() const { return pair_->error_order; }

  // The error norm of a step of h (NaN when the step is not finite); the
  // step is kept in y_new_ for accept.
  double try_step(double /*t*/, double h, Cost& cost) {
    const EmbeddedPair& p = *pair_;
    if (!have_first_) {
      problem_->flat_rhs(y_.data(), k_[0].data());
      ++cost.rhs_evals;
      have_first_ = true;
    }
    // stages 1 .. stages-1; the FSAL stage (if any) is among them and its
    // state is y_new itself
    for (int i = 1; i < p.stages; ++i) {
      stage_ = y_ + h * combine(&p.a[static_cast<std::size_t>(i * p.total)], i);
      problem_->flat_rhs(stage_.data(), k_[static_cast<std::size_t>(i)].data());
      ++cost.rhs_evals;
    }
    y_new_ = p.fsal < p.stages ? stage_for(p.fsal, h) : FlatState(y_ + h * combine(p.b.data(), p.stages));
    return y_new_.allFinite() ? error_norm(h) : std::numeric_limits<double>::quiet_NaN();
  }

  void accept(double /*t*/, double /*h*/, Cost& cost) {
    const EmbeddedPair& p = *pair_;
    y_ = y_new_;
    // the next step's first stage
    if (p.fsal < p.stages) {
      k_[0] = k_[static_cast<std::size_t>(p.fsal)];
    } else {
      problem_->flat_rhs(y_.data(), k_[0].data());
      ++cost.rhs_evals;
    }
  }

  void state(FlatState& y) const { y = y_; }
  void interpolate(double, FlatState& y) const { y = y_; }

 private:
  // sum_j w_j k_j over the first count stages
  FlatState combine(const double* w, int count) const {
    FlatState sum = FlatState::Zero();
    for (int j = 0; j < count; ++j)
      if (w[j] != 0.0) sum += w[j] * k_[static_cast<std::size_t>(j)];
    return sum;
  }

  // the FSAL stage's state: its row of A is b, so it is y_new
  FlatState stage_for(int i, double h) const {
    return y_ + h * combine(&pair_->a[static_cast<std::size_t>(i * pair_->total)], i);
  }

  double error_norm(double h) const {
    const FlatState scale =
        (tol_.atol + tol_.rtol * y_.cwiseAbs().cwiseMax(y_new_.cwiseAbs()).array()).matrix();
    const FlatState e = h * combine(pair_->e.data(), pair_->stages);
    return std::sqrt((e.array() / scale.array()).square().sum() / static_cast<double>(kFlatSize));
  }

  const Problem* problem_;
  const EmbeddedPair* pair_;
  Tolerances tol_;
  FlatState y_, y_new_, stage_;
  std::array<FlatState, kMaxStages> k_;
  bool have_first_ = false;
};

MethodInfo facts_of(const EmbeddedPair& p, std::string name) {
  return {.name = std::move(name),
          .family = "rk-adaptive",
          .declared_order = p.order,
          .adaptive = true,
          .controller = "pi",
          .description = "adaptive explicit RK on the " + p.name + " pair (order " + std::to_string(p.order) + ", " +
                         std::to_string(p.stages) + " stages" + (p.fsal < p.stages ? ", FSAL" : "") +
                         ", PI controller by default) on the flat view; steps clamped onto the outputs"};
}

}  // namespace

RungeKuttaAdaptive::RungeKuttaAdaptive(EmbeddedPair pair, std::string name)
    : Integrator(facts_of(pair, std::move(name))), pair_(std::move(pair)) {
  const EmbeddedPair& p = pair_;
  const auto n = static_cast<std::size_t>(p.total);
  // the stage loop runs over the attempt's stages only: no dense-output stages
  const bool fits = p.stages >= 2 && p.stages == p.total && p.total <= kMaxStages && p.fsal >= 1 &&
                    p.fsal <= p.stages && p.error_order >= 1 && p.a.size() == n * n && p.c.size() == n &&
                    p.b.size() == n && p.e.size() == n && p.e3.empty();
  if (!fits) throw InputError("embedded pair '" + p.name + "' has inconsistent sizes for a flat adaptive method", "pair");
  (void)p.tableau(p.name);  // b against its order conditions
}

RunResult RungeKuttaAdaptive::integrate(const Problem& problem, const RunOptions& options) const {
  FlatPairStepper stepper(problem, pair_, tolerances_of(options));
  return drive_adaptive(problem, options, pair_.order, stepper, controller_of(controller(), options));
}

}  // namespace rb

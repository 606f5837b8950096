#include "integrators/steppers/flat_embedded.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "integrators/adaptive.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The PI controller of MuntheKaasAdaptive (see the header), as a part of its
// own: it decides on an attempt's error norm and sets the next step.
class PiController {
 public:
  explicit PiController(int error_order)
      : k_(error_order), alpha_(0.7 / error_order), beta_(0.4 / error_order) {}

  // err: the attempt's error norm (1 = the tolerance); h becomes the next step
  Attempt decide(double err, double t, double& h) {
    if (!std::isfinite(err)) {
      // a trial step past where F is finite was too large: shrink it hard;
      // again and again, and the run has diverged
      if (++nonfinite_trials_ > kMaxNonFiniteTrials) {
        char text[160];
        std::snprintf(text, sizeof text, "the state is not finite beyond t = %.9g (%d trial steps past it, the last of %.3g)",
                      t, nonfinite_trials_, h);
        throw StepFailure(Status::diverged, text);
      }
      return reject(h, kFacMin);
    }
    if (err > 1.0) return reject(h, std::max(kFacMin, kSafety * std::pow(err, -1.0 / k_)));
    const double fac = kSafety * std::pow(std::max(err, 1e-10), -alpha_) * std::pow(err_prev_, beta_);
    err_prev_ = std::max(err, 1e-4);
    h *= std::clamp(fac, kFacMin, rejected_last_ ? 1.0 : kFacMax);
    rejected_last_ = false;
    return Attempt::accepted;
  }

 private:
  static constexpr double kSafety = 0.9, kFacMin = 0.2, kFacMax = 10.0;
  static constexpr int kMaxNonFiniteTrials = 10;

  Attempt reject(double& h, double factor) {
    h *= factor;
    rejected_last_ = true;
    return Attempt::rejected;
  }

  int k_;
  double alpha_, beta_;
  double err_prev_ = 1e-4;
  bool rejected_last_ = false;
  int nonfinite_trials_ = 0;
};

// The pair's steps for drive_adaptive (see integrators/adaptive.hpp).
class FlatPairStepper {
 public:
  static constexpr bool dense_output = false;

  FlatPairStepper(const Problem& problem, const EmbeddedPair& pair, const Tolerances& tol)
      : problem_(&problem), pair_(&pair), tol_(tol), controller_(pair.error_order), y_(problem.y0()) {}

  Attempt attempt(double t, double& h, Cost& cost) {
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
    const double err = y_new_.allFinite() ? error_norm(h) : kNaN;
    if (controller_.decide(err, t, h) == Attempt::rejected) return Attempt::rejected;
    y_ = y_new_;
    // the next step's first stage
    if (p.fsal < p.stages) {
      k_[0] = k_[static_cast<std::size_t>(p.fsal)];
    } else {
      problem_->flat_rhs(y_.data(), k_[0].data());
      ++cost.rhs_evals;
    }
    return Attempt::accepted;
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
  PiController controller_;
  FlatState y_, y_new_, stage_;
  std::array<FlatState, kMaxStages> k_;
  bool have_first_ = false;
};

}  // namespace

RungeKuttaAdaptive::RungeKuttaAdaptive(EmbeddedPair pair, std::string name)
    : pair_(std::move(pair)), name_(std::move(name)) {
  const EmbeddedPair& p = pair_;
  const auto n = static_cast<std::size_t>(p.total);
  // the stage loop runs over the attempt's stages only: no dense-output stages
  const bool fits = p.stages >= 2 && p.stages == p.total && p.total <= kMaxStages && p.fsal >= 1 &&
                    p.fsal <= p.stages && p.error_order >= 1 && p.a.size() == n * n && p.c.size() == n &&
                    p.b.size() == n && p.e.size() == n && p.e3.empty();
  if (!fits) throw InputError("embedded pair '" + p.name + "' has inconsistent sizes for a flat adaptive method", "pair");
  (void)p.tableau(p.name);  // b against its order conditions
}

std::string RungeKuttaAdaptive::description() const {
  const EmbeddedPair& p = pair_;
  return "adaptive explicit RK on the " + p.name + " pair (order " + std::to_string(p.order) + ", " +
         std::to_string(p.stages) + " stages" + (p.fsal < p.stages ? ", FSAL" : "") +
         ", PI controller) on the flat view; steps clamped onto the outputs";
}

RunResult RungeKuttaAdaptive::integrate(const Problem& problem, const RunOptions& options) const {
  FlatPairStepper stepper(problem, pair_, tolerances_of(options));
  return drive_adaptive(problem, options, pair_.order, stepper);
}

}  // namespace rb

#include "integrators/families/rkmk/munthe_kaas_adaptive.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "integrators/stage_terms.hpp"
#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

// (u, z) stacked: a stage's (dexpinv_u(omega), G(z)), or a step's increment
// (u, z - z_n). The pair works on this vector as on any ODE's state.
using LieVec = Eigen::Matrix<double, 3 + kZSize, 1>;
constexpr int kLieSize = 3 + kZSize;

// The pair's steps for drive_estimating (integrators/adaptive_loops.hpp), on the
// shared try/accept skeleton: an error estimate for the controller, which
// decides. General: the ball has
// inertia (RollingBall::has_inertia()), so that its evaluation is inlined.
template <bool Dense, bool General>
class LieStepper : public EmbeddedPair<LieStepper<Dense, General>> {
 public:
  static constexpr bool dense_output = Dense;

  LieStepper(const Problem& problem, const Tableau& tableau, const Tolerances& tol, const std::vector<double>& outputs)
      : problem_(&problem),
        tableau_(&tableau),
        tol_(tol),
        outputs_(&outputs),
        attempt_(tableau.attempt_stages()),
        fsal_(tableau.fsal_stage().value_or(-1)),
        fsal_in_attempt_(tableau.fsal_in_attempt()) {
    R_ = rotation_of(problem.y0());
    z_ = z_of(problem.y0());
    const int total = tableau.total_stages();
    for (int i = 0; i < total; ++i)
      rows_[static_cast<std::size_t>(i)] =
          StageTerms::Row(&tableau.a_row_major()[static_cast<std::size_t>(i * total)], i);
    b_ = StageTerms::Row(tableau.b_weights().data(), attempt_);
    e_ = StageTerms::Row(tableau.e().data(), attempt_);
    if (!tableau.e_stretched().empty()) e3_ = StageTerms::Row(tableau.e_stretched().data(), attempt_);
    if constexpr (Dense) dense_y_.reserve(8);
  }

  int error_order() const { return tableau_->error_order(); }

  void first_stage(Cost& cost) {
    stage_lie_rhs_on_path<General>(*problem_, R_, z_.data(), omega_first_.data(), g_first_.data(), cost);
    ++cost.rhs_evals;
  }

  // the step (u_n+1, z_n+1 - z_n) kept in w_new_ for commit
  double attempt(double h, Cost& cost) {
    set_stage(0, omega_first_, g_first_);
    for (int i = 1; i < attempt_; ++i) evaluate_stage(i, h, R_, z_, cost);
    if (fsal_in_attempt_) {
      w_new_ = w_fsal_;
    } else {
      w_new_ = combine(b_, h);
    }
    return error_norm(w_new_, h);
  }
  bool tried_finite() const { return w_new_.allFinite(); }

  bool commit(double t, double h, Cost& cost) {
    R_prev_ = R_;
    z_prev_ = z_;
    R_ = so3_exp(w_new_.head<3>()) * R_prev_;
    ++cost.exp_evals;
    z_ = z_prev_ + w_new_.tail<kZSize>();
    // the next step's first stage
    if (fsal_in_attempt_) {
      omega_first_ = omega_fsal_;
      g_first_ = k_[static_cast<std::size_t>(fsal_)].tail<kZSize>();
    } else {
      // its margins stay in cost.watch for the driver's look after the
      // next attempt, whose first stage this is
      first_stage(cost);
    }
    if constexpr (Dense) dense_outputs(t, h, w_new_, cost);
    return true;
  }

  void state(FlatState& y) const {
    set_rotation(y, R_);
    y.tail<kZSize>() = z_;
  }
  // back to the step's start after the driver refused the step accepted
  // last (its dense output went beyond a limit)
  void go_back(const FlatState& /*y, kept as R_prev_, z_prev_*/) {
    R_ = R_prev_;
    z_ = z_prev_;
  }

  // The outputs were computed in attempt (they cost stages and exps, counted
  // there); a time not among them can only lie within rounding of the step's
  // end, where the state is the step's.
  void interpolate(double t, FlatState& y) const {
    for (std::size_t i = 0; i < dense_t_.size(); ++i)
      if (dense_t_[i] == t) {
        y = dense_y_[i];
        return;
      }
    state(y);
  }

 private:
  // h sum_j w_j k_j. Inlined (some of its calls were out of line: 256
  // instructions a step of rkmk-f78-adaptive ran there).
  [[gnu::always_inline]] LieVec combine(const StageTerms::Row& w, double h) const {
    return h * w.combination<LieVec>(k_);
  }

  // k_i = (u', z'), by parts rather than by Eigen's comma initializer
  void set_stage(int i, const Vec3& du, const ZState& dz) {
    LieVec& k = k_[static_cast<std::size_t>(i)];
    k.head<3>() = du;
    k.tail<kZSize>() = dz;
  }

  // k_i = (dexpinv_U(omega(R_i, Z)), G(R_i, Z)) at (U, Z - z_n) =
  // h sum_j a_ij k_j, (R_n, z_n) the step's start; the stage orientation
  // R_i = exp(hat(U)) R_n is formed only where R enters (anisotropic ball).
  void evaluate_stage(int i, double h, const Mat3& R_n, const ZState& z_n, Cost& cost) {
    const LieVec w = combine(rows_[static_cast<std::size_t>(i)], h);
    const ZState z = z_n + w.tail<kZSize>();
    Vec3 omega;
    ZState g;
    if (General && problem_->model().anisotropic()) {
      stage_lie_rhs_on_path<General>(*problem_, Mat3(so3_exp(w.head<3>()) * R_n), z.data(), omega.data(), g.data(),
                                     cost);
      ++cost.exp_evals;
    } else {
      stage_lie_rhs_on_path<General>(*problem_, R_n, z.data(), omega.data(), g.data(), cost);
    }
    ++cost.rhs_evals;
    set_stage(i, dexpinv(w.head<3>(), omega), g);
    ++cost.dexpinv_evals;
    if (i == fsal_) {
      w_fsal_ = w;
      omega_fsal_ = omega;
    }
  }

  // The controller's error: RMS of h sum e_i k_i against the scales
  // (Hairer's stretched combination of two estimates for DP853).
  double error_norm(const LieVec& w_new, double h) const {
    LieVec scale;
    scale.head<3>().setConstant(rotation_scale(tol_));
    scale.tail<kZSize>() = value_scale(tol_, z_, ZState(z_ + w_new.tail<kZSize>()));
    const double e2 = scaled_squares(combine(e_, h), scale);
    if (e3_.count == 0) return rms_error(e2, kLieSize);
    return stretched_rms_error(e2, scaled_squares(combine(e3_, h), scale), kLieSize);
  }

  // Every output strictly inside (t, t + h): the extra stages once, then
  // u(theta), z(theta) from the dense weights and R = exp(hat(u)) R_n.
  void dense_outputs(double t, double h, const LieVec& w_new, Cost& cost) {
    const Tableau& p = *tableau_;
    dense_t_.clear();
    dense_y_.clear();
    const std::vector<double>& out = *outputs_;
    while (next_out_ < out.size() && out[next_out_] <= t) ++next_out_;
    if (next_out_ == out.size() || out[next_out_] >= t + h) return;
    // the stages only the dense output needs; the FSAL one among them is
    // the next step's first stage, already evaluated (its dexpinv differs)
    if (fsal_ >= attempt_) {
      set_stage(fsal_, dexpinv(w_new.head<3>(), omega_first_), g_first_);
      ++cost.dexpinv_evals;
    }
    for (int i = attempt_; i < p.total_stages(); ++i)
      if (i != fsal_) evaluate_stage(i, h, R_prev_, z_prev_, cost);
    for (std::size_t m = next_out_; m < out.size() && out[m] < t + h; ++m) {
      const double theta = (out[m] - t) / h;
      LieVec sum = LieVec::Zero();
      for (int j = 0; j < p.total_stages(); ++j) {
        const double* d = &p.dense()[static_cast<std::size_t>(j * p.dense_degree())];
        double b = 0.0;
        for (int q = p.dense_degree() - 1; q >= 0; --q) b = (b + d[q]) * theta;
        sum += b * k_[static_cast<std::size_t>(j)];
      }
      const LieVec w = h * sum;
      FlatState y;
      set_rotation(y, so3_exp(w.head<3>()) * R_prev_);
      ++cost.exp_evals;
      y.tail<kZSize>() = z_prev_ + w.tail<kZSize>();
      dense_t_.push_back(out[m]);
      dense_y_.push_back(y);
    }
  }

  const Problem* problem_;
  const Tableau* tableau_;
  Tolerances tol_;
  const std::vector<double>* outputs_;
  int attempt_;           // the stages of an attempt
  int fsal_;              // the FSAL stage, -1 without one
  bool fsal_in_attempt_;  // the error estimate uses it (BS32, DP54)
  Mat3 R_, R_prev_;
  ZState z_, z_prev_;
  std::array<LieVec, kMaxStages> k_;
  std::array<StageTerms::Row, kMaxStages> rows_;
  StageTerms::Row b_, e_, e3_;
  Vec3 omega_first_, omega_fsal_;  // omega at the step's start; at the FSAL stage
  ZState g_first_;
  LieVec w_fsal_;
  LieVec w_new_;  // the step tried last
  std::size_t next_out_ = 0;
  std::vector<double> dense_t_;
  std::vector<FlatState> dense_y_;
};

}  // namespace

namespace {

std::string description_of(const Tableau& p, const std::string& controller, bool use_dense) {
  const bool fsal_in_attempt = p.fsal_in_attempt();
  const int per_attempt = p.attempt_stages() - 1 + (fsal_in_attempt ? 0 : 1);
  // the stages past the attempt's, less the FSAL one (evaluated for the next step)
  const int extra = p.total_stages() - p.attempt_stages() - (p.fsal_stage() && !fsal_in_attempt ? 1 : 0);
  std::string text = "adaptive Runge-Kutta-Munthe-Kaas on the " + p.name() + " pair (order " +
                     std::to_string(p.order()) + ", error estimate on (u, z), " + controller_title(controller) +
                     " controller): " + std::to_string(per_attempt) + " rhs and " +
                     std::to_string(p.attempt_stages() - 1) + " dexpinv a step, one exp";
  if (use_dense)
    text += "; outputs by its order-" + std::to_string(p.dense_order()) + " dense output through exp" +
            (extra > 0 ? " (" + std::to_string(extra) + " extra rhs a step with outputs)" : std::string());
  else text += "; steps clamped onto the outputs";
  return text;
}

}  // namespace

std::unique_ptr<Integrator> rkmk_adaptive(Tableau tableau, std::string name, const std::string& controller,
                                          bool use_dense) {
  require_embedded_pair(tableau, controller);
  use_dense = use_dense && tableau.dense_order() > 0;
  MethodInfo info{.name = std::move(name),
                  .family = "rkmk-adaptive",
                  .declared_order = tableau.order(),
                  .embedded_order = tableau.embedded_order(),
                  .controller = controller,
                  .description = description_of(tableau, controller, use_dense),
                  .tableau = tableau.name(),
                  .on_group = true};
  return adaptive_method(
      std::move(info), [tableau = std::move(tableau), use_dense](const Problem& problem, const RunOptions& options,
                                                                 const Tolerances& tol, auto&& drive) {
        const std::vector<double> outputs = output_times_of(problem, options);
        // the four steppers: dense output or not, a ball with inertia or not
        auto run = [&]<bool Dense, bool General>() {
          LieStepper<Dense, General> stepper(problem, tableau, tol, outputs);
          return drive(stepper);
        };
        const bool general = problem.model().has_inertia();
        if (use_dense) return general ? run.template operator()<true, true>() : run.template operator()<true, false>();
        return general ? run.template operator()<false, true>() : run.template operator()<false, false>();
      });
}

}  // namespace rb

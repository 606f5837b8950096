#pragma once
// The Runge-Kutta-Munthe-Kaas stepper (docs/model.md, "The methods compared"),
// one stage loop for fixed steps and for embedded pairs: over a step with R_n
// fixed, integrate u' = dexpinv_u(omega(z)), u(t_n) = 0, together with
// z' = G(z) by an explicit tableau, then R_{n+1} = phi(u_{n+1}) R_n for the
// coordinate map phi (exp, or the Cayley map). R stays in SO(3) to rounding.
//
// step<Estimate> is the one stage loop. Estimate = false: the propagating
// stages (Tableau::stages()), no error, run by drive_fixed_step through
// operator(). Estimate = true: the attempt's stages
// (Tableau::attempt_stages()) and the error norm (error_norm.hpp), run by
// drive_estimating through the EmbeddedPair protocol. Both sum every stage
// and the new state with StageTerms::Row::sum, in the same order, so that a
// pair's new state is its tableau's fixed step bit for bit.
//
// The pair (docs/integrators.md, the rkmk-adaptive family):
// - The local error is estimated on (u, z) only, never on R's entries: u's
//   three components are angles, measured against atol + rtol (R's entries
//   are of size 1, as a flat method sees them); z's against
//   atol + rtol max(|z_n,i|, |z_n+1,i|). Norm: root mean square (Hairer's),
//   stretched for DP853.
// - Outputs inside a step come from the pair's dense output mapped through
//   exp: R(t_n + theta h) = exp(hat(u(theta))) R_n, z(theta) likewise (one
//   exp each; DP853 needs its 3 extra stages once per step that holds an
//   output). Without a dense output (Dense = false) steps are clamped to
//   land on every output time.
// - FSAL: the right-hand side at (t_n+1, z_n+1) is the next step's first
//   stage; the stage's dexpinv differs (u = 0 there), the evaluation not.
// Cost per accepted step: (stages - 1) rhs evaluations and dexpinv
// applications in each attempt, plus the FSAL stage's rhs where the error
// estimate does not use it, and one exp; each output adds one exp.
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "integrators/driver.hpp"
#include "integrators/run_book.hpp"
#include "integrators/stage_terms.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"
#include "problems/cayley.hpp"
#include "problems/so3.hpp"

namespace rb {

// The rotation a homogeneous ball's Lie-view right-hand side is given: it
// does not read it (RollingBall::lie_rhs).
inline const Mat3 kAnyRotation = Mat3::Identity();

// exp by Rodrigues' formula and its dexpinv (closed form, series or the
// seminar's). Inlined into the stage loop: out of line, each dexpinv passed
// its vectors through memory (callgrind: 76 instructions a call).
struct ExpCoordinates {
  DexpinvKind kind;
  // Called by a fixed step where a stage's dexpinv is not finite: past the
  // chart's edge (|u| >= kDexpinvMaxAngle, the closed form's pole) the step
  // cannot be taken in these coordinates, which is the status chart-limit,
  // not a divergence of the state. (A pair's step is rejected and shrunk.)
  [[gnu::cold, gnu::noinline]] void check_chart(double angle) const {
    // a NaN stage (the state itself not finite) is no chart's edge
    if (kind == DexpinvKind::exact && angle >= kDexpinvMaxAngle) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "a stage turns the ball by |u| = %.4g rad, past the exponential chart's edge (%.4g rad, "
                    "dexpinv's pole at 2 pi): the step is too large for these coordinates",
                    angle, kDexpinvMaxAngle);
      throw StepFailure(Status::chart_limit, text);
    }
  }
  // Whether check_chart might throw at this stage: a bound a little below
  // the edge (every |u| >= kDexpinvMaxAngle passes it), tested where u is
  // known, so that the exact test runs only near the edge. |u|^2 is
  // dexpinv's (squared_angle), so that GCC forms it once for both (Eigen's
  // packed squaredNorm was formed again: rkmk4, 21 instructions a step;
  // docs/performance-history.md, tenth pass).
  [[gnu::always_inline]] bool near_chart_edge(const Vec3& u) const {
    constexpr double bound = kDexpinvMaxAngle * (1.0 - 1e-9);
    return squared_angle(u) >= bound * bound;
  }
  [[gnu::always_inline]] Mat3 exp(const Vec3& u) const { return so3_exp(u); }
  [[gnu::always_inline]] Vec3 dexpinv(const Vec3& u, const Vec3& w) const { return rb::dexpinv(u, w, kind); }
};

// The same with the closed-form dexpinv known at compile time (every pair,
// and the fixed steps of the closed form, rkmk4 among them): the stages then
// test no kind (callgrind, rkmk4: 30 instructions a step; docs/performance-history.md,
// ninth pass). The other kinds keep ExpCoordinates' test.
struct ClosedFormExpCoordinates : ExpCoordinates {
  ClosedFormExpCoordinates() : ExpCoordinates{DexpinvKind::exact} {}
  [[gnu::always_inline]] Vec3 dexpinv(const Vec3& u, const Vec3& w) const {
    return rb::dexpinv(u, w, DexpinvKind::exact);
  }
};

// The Cayley map and its dcayinv, counted as exp and dexpinv.
struct CayleyCoordinates {
  [[gnu::always_inline]] Mat3 exp(const Vec3& u) const { return so3_cay(u); }
  [[gnu::always_inline]] Vec3 dexpinv(const Vec3& u, const Vec3& w) const { return dcayinv(u, w); }
  // dcayinv has no pole
  bool near_chart_edge(const Vec3& /*u*/) const { return false; }
  void check_chart(double /*angle*/) const {}
};

// The stages' derivatives of a step. A pair's (and a fixed step's of any
// stage count) are held in the frame that makes the stepper, so that a step
// allocates nothing; a fixed step of N stages known at compile time keeps
// its own, local, where they stay in registers.
template <std::size_t N>
struct StageDerivatives {
  std::array<Vec3, N> K;    // u' at the stages
  std::array<ZState, N> L;  // z' at the stages
};
using RkmkStages = StageDerivatives<kMaxStages>;

// S stages unrolled (S = 0: any number; the pairs), of Shape (a fixed step
// of S <= 4 stages whose rows' patterns of zeros are known at compile time:
// StageTerms::shape(S) is Shape) or kRuntimeShape. Coordinates: exp and
// dexpinv, or cay and dcayinv. Dense: the pair's outputs by its dense
// output, else clamped steps (Dense concerns the pair only). General: the
// ball has inertia (RollingBall::has_inertia()), so that every stage's
// evaluation is inlined on that code path, and only there the stages
// orient an anisotropic ball (the homogeneous ball's fixed step then
// carries none of that code: docs/performance-history.md, "rkmk4 at the limit").
template <int S, class Coordinates, bool Dense = false, bool General = false, StageShape Shape = kRuntimeShape>
class RkmkStepper : public EmbeddedPair<RkmkStepper<S, Coordinates, Dense, General, Shape>> {
 public:
  static constexpr bool dense_output = Dense;

  // For fixed steps.
  RkmkStepper(const Problem& problem, const Tableau& tableau, const StageTerms& terms, Coordinates map,
              RkmkStages& stages)
      : problem_(problem),
        tableau_(tableau),
        terms_(terms),
        map_(map),
        anisotropic_(problem.model().anisotropic()),
        frame_(stages),
        fsal_(tableau.fsal_stage().value_or(-1)),
        fsal_in_attempt_(tableau.fsal_in_attempt()) {
    // a shape that is not the tableau's would sum the wrong terms
    if constexpr (Shape != kRuntimeShape)
      if (terms.shape(S) != Shape) throw std::logic_error("RkmkStepper: the tableau's stage shape is not Shape");
  }

  // For the embedded pair: from the problem's start, with the run's
  // tolerances and output times.
  RkmkStepper(const Problem& problem, const Tableau& tableau, const StageTerms& terms, Coordinates map,
              RkmkStages& stages, const Tolerances& tol, const std::vector<double>& outputs)
      : RkmkStepper(problem, tableau, terms, map, stages) {
    tol_ = tol;
    outputs_ = &outputs;
    y_ = problem.y0();
    R_ = rotation_of(y_);
    z_ = z_of(y_);
    if constexpr (Dense) dense_y_.reserve(8);
  }

  // ---- the fixed-step functor (drive_fixed_step) ----

  // Run only by drive_fixed_step, which never reads Cost::watch.near: its
  // stages skip that test (Cost::note). Every stage's validity margins are
  // noted in cost. Inlined into the driver's loop: called once a step, it
  // ran about a twentieth slower (docs/performance-history.md, "rkmk4 at the limit",
  // fifth pass).
  [[gnu::always_inline]] void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) {
    if constexpr (S > 0) {
      StageDerivatives<S> local;
      fixed_step(local, y, next, h, cost);
    } else {
      fixed_step(frame_, y, next, h, cost);
    }
  }

  // ---- the embedded pair (drive_estimating, EmbeddedPair) ----

  int error_order() const { return tableau_.error_order(); }

  void first_stage(Cost& cost) {
    stage_lie_rhs_on_path<General>(problem_, R_, z_.data(), omega_first_.data(), g_first_.data(), cost);
    ++cost.rhs_evals;
  }

  // the step (u_n+1, z_n+1 - z_n) kept in u_new_, dz_new_ for commit
  double attempt(double h, Cost& cost) {
    frame_.K[0] = omega_first_;
    frame_.L[0] = g_first_;
    cost.rhs_evals += terms_.attempt - 1;
    return step<true>(frame_, R_, z_, h, u_new_, dz_new_, cost);
  }
  bool tried_finite() const { return u_new_.allFinite() && dz_new_.allFinite(); }

  bool commit(double t, double h, Cost& cost) {
    y_prev_ = y_;
    R_prev_ = R_;
    z_prev_ = z_;
    advance(y_prev_, z_prev_, u_new_, dz_new_, y_);
    ++cost.exp_evals;
    R_ = rotation_of(y_);
    z_ = z_of(y_);
    // the next step's first stage
    if (fsal_in_attempt_) {
      omega_first_ = omega_fsal_;
      g_first_ = frame_.L[static_cast<std::size_t>(fsal_)];
    } else {
      // its margins stay in cost.watch for the driver's look after the
      // next attempt, whose first stage this is
      first_stage(cost);
    }
    if constexpr (Dense) dense_outputs(t, h, cost);
    return true;
  }

  void state(FlatState& y) const { y = y_; }
  // back to the step's start after the driver refused the step accepted
  // last (its dense output went beyond a limit)
  void go_back(const FlatState& /*y, kept as y_prev_*/) {
    y_ = y_prev_;
    R_ = R_prev_;
    z_ = z_prev_;
  }

  // The outputs were computed in commit (they cost stages and exps, counted
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
  // A fixed step from y into next, its stages' derivatives in f.
  template <class Frame>
  [[gnu::always_inline]] void fixed_step(Frame& f, const FlatState& y, FlatState& next, double h, Cost& cost) {
    const ZState z = z_of(y);
    // R_n, read in place: the homogeneous ball's right-hand side does not
    // read R, so its stages are given any rotation and R_n is read once, by
    // the update; only an anisotropic ball's stages take a copy
    const Eigen::Map<const RowMajorMat3> Rn(y.data() + kOffsetR);
    Mat3 R_copy;
    const Mat3* R = &kAnyRotation;
    if (General && anisotropic_) {
      R_copy = Rn;
      R = &R_copy;
    }
    // the first stage, at u = 0 (dexpinv the identity) and R itself
    rhs<false>(*R, z, f.K[0], f.L[0], cost);
    Vec3 u;
    ZState dz;
    step<false>(f, *R, z, h, u, dz, cost);
    advance(y, z, u, dz, next);
    cost.rhs_evals += S > 0 ? S : terms_.stages;
    ++cost.exp_evals;
  }

  // phi(u) R_n into out (9 numbers, row-major) from R_n at Rn (the same):
  // the new state's R, as the step's update and a pair's FSAL stage form
  // it (a product into a column-major matrix rounds differently).
  [[gnu::always_inline]] void rotate(const double* Rn, const Vec3& u, double* out) const {
    Eigen::Map<RowMajorMat3>(out).noalias() = map_.exp(u) * Eigen::Map<const RowMajorMat3>(Rn);
  }
  // The new state from the step's start y (its z given) and the increment
  // (u, dz).
  [[gnu::always_inline]] void advance(const FlatState& y, const ZState& z, const Vec3& u, const ZState& dz,
                                      FlatState& next) const {
    rotate(y.data() + kOffsetR, u, next.data() + kOffsetR);
    next.tail<kZSize>() = z + dz;
  }

  // The one stage loop: stages 1.. from the first (in f.K[0], f.L[0]) at
  // (R, z), the step's increment (u, dz) = h sum b_j (K_j, L_j); with
  // Estimate the attempt's stages and the error norm, else 0.
  template <bool Estimate, class Frame>
  [[gnu::always_inline]] double step(Frame& f, const Mat3& R, const ZState& z, double h, Vec3& u, ZState& dz,
                                     Cost& cost) {
    if constexpr (!Estimate && S > 0) {
      // a known stage count unrolled in full, each stage's index a
      // compile-time constant (as a loop, GCC kept rkmk4's three later
      // stages one loop body, callgrind: 487 instructions run 3 times)
      [&]<std::size_t... I>(std::index_sequence<I...>) __attribute__((always_inline)) {
        (stage<false>(f, std::integral_constant<std::size_t, I + 1>{}, R, z, h, cost), ...);
      }
      (std::make_index_sequence<S - 1>{});
      terms_.b.template sum_first<S, shape_row(Shape, S)>(u, h, f.K);
      terms_.b.template sum_first<S, shape_row(Shape, S)>(dz, h, f.L);
    } else {
      const int stages = Estimate ? terms_.attempt : terms_.stages;
      for (std::size_t i = 1; i < static_cast<std::size_t>(stages); ++i) stage<Estimate>(f, i, R, z, h, cost);
      if (Estimate && fsal_in_attempt_) {
        // the FSAL stage is the new state (its row of A is b)
        u = u_fsal_;
        dz = dz_fsal_;
      } else {
        terms_.b.sum(u, h, f.K);
        terms_.b.sum(dz, h, f.L);
      }
    }
    if constexpr (Estimate) return error_norm(z, dz, h);
    return 0.0;
  }

  // Stage i at (U, Z - z) = h sum_j a_ij (K_j, L_j), from the step's start
  // (R, z): K_i = dexpinv_U(omega(R_i, Z)), L_i = G(R_i, Z); the stage
  // orientation R_i = phi(U) R is formed only where R enters (anisotropic
  // ball). The FSAL stage's Z is z + dz, exactly the new state's. Index:
  // std::size_t, or a compile-time constant (std::integral_constant) in a
  // fixed step's unrolled loop, whose sums then address f at compile time.
  template <bool Estimate, class Frame, class Index>
  [[gnu::always_inline]] void stage(Frame& f, Index i, const Mat3& R, const ZState& z, double h, Cost& cost) {
    const StageTerms::Row& row = terms_.a[i];
    ZState Z;
    Vec3 U;
    const bool fsal = Estimate && static_cast<int>(i) == fsal_;
    if (fsal) {
      row.sum(dz_fsal_, h, f.L);
      Z = z + dz_fsal_;
    } else {
      row.template sum_before<Shape>(i, Z, z, h, f.L);
    }
    row.template sum_before<Shape>(i, U, h, f.K);
    Vec3 omega;
    if (General && anisotropic_) {
      // R enters omega and G: evaluate at the stage's own orientation, the
      // FSAL stage's the new state's (the next step's first stage)
      if (fsal) {
        std::array<double, 9> R_new;
        rotate(y_.data() + kOffsetR, U, R_new.data());
        rhs<Estimate>(Mat3(Eigen::Map<const RowMajorMat3>(R_new.data())), Z, omega, f.L[i], cost);
      } else {
        rhs<Estimate>(Mat3(map_.exp(U) * R), Z, omega, f.L[i], cost);
      }
      ++cost.exp_evals;
    } else {
      rhs<Estimate>(R, Z, omega, f.L[i], cost);
    }
    f.K[i] = map_.dexpinv(U, omega);
    ++cost.dexpinv_evals;
    if constexpr (!Estimate) {
      // tested first on U, known when the stage starts, not on K, its last
      // number: a branch on K held back everything after it (a tenth of
      // rkmk4's step; docs/performance-history.md, "rkmk4 at the limit")
      if (map_.near_chart_edge(U)) [[unlikely]]
        if (!std::isfinite(f.K[i].x())) map_.check_chart(U.norm());
    }
    if (fsal) {
      u_fsal_ = U;
      omega_fsal_ = omega;
    }
  }

  // A stage's evaluation on the code path General. A fixed step's notes no
  // near-limit margins (drive_fixed_step never reads them); a pair's does.
  template <bool Estimate>
  [[gnu::always_inline]] void rhs(const Mat3& R, const ZState& Z, Vec3& omega, ZState& dz, Cost& cost) const {
    stage_lie_rhs_on_path<General, Estimate>(problem_, R, Z.data(), omega.data(), dz.data(), cost);
  }

  // The controller's error: RMS of h sum e_i (K_i, L_i) against the scales
  // (Hairer's stretched combination of two estimates for DP853).
  double error_norm(const ZState& z, const ZState& dz, double h) const {
    LieVec scale, err;
    scale.head<3>().setConstant(rotation_scale(tol_));
    scale.tail<kZSize>() = value_scale(tol_, z, ZState(z + dz));
    const double e2 = scaled_squares(estimate(terms_.e, h, err), scale);
    if (terms_.e3.count == 0) return rms_error(e2, kLieSize);
    return stretched_rms_error(e2, scaled_squares(estimate(terms_.e3, h, err), scale), kLieSize);
  }
  // (u, z) stacked: an error estimate h sum w_j (K_j, L_j)
  using LieVec = Eigen::Matrix<double, 3 + kZSize, 1>;
  static constexpr int kLieSize = 3 + kZSize;
  [[gnu::always_inline]] const LieVec& estimate(const StageTerms::Row& w, double h, LieVec& out) const {
    Vec3 eu;
    ZState ez;
    w.sum(eu, h, frame_.K);
    w.sum(ez, h, frame_.L);
    out.head<3>() = eu;
    out.tail<kZSize>() = ez;
    return out;
  }

  // Every output strictly inside (t, t + h): the extra stages once, then
  // u(theta), z(theta) from the dense weights and R = exp(hat(u)) R_n.
  void dense_outputs(double t, double h, Cost& cost) {
    const Tableau& p = tableau_;
    dense_t_.clear();
    dense_y_.clear();
    const std::vector<double>& out = *outputs_;
    while (next_out_ < out.size() && out[next_out_] <= t) ++next_out_;
    if (next_out_ == out.size() || out[next_out_] >= t + h) return;
    // the stages only the dense output needs; the FSAL one among them is
    // the next step's first stage, already evaluated (its dexpinv differs)
    if (fsal_ >= terms_.attempt) {
      frame_.K[static_cast<std::size_t>(fsal_)] = map_.dexpinv(u_new_, omega_first_);
      frame_.L[static_cast<std::size_t>(fsal_)] = g_first_;
      ++cost.dexpinv_evals;
    }
    for (int i = terms_.attempt; i < p.total_stages(); ++i)
      if (i != fsal_) {
        stage<true>(frame_, static_cast<std::size_t>(i), R_prev_, z_prev_, h, cost);
        ++cost.rhs_evals;
      }
    for (std::size_t m = next_out_; m < out.size() && out[m] < t + h; ++m) {
      const double theta = (out[m] - t) / h;
      Vec3 su = Vec3::Zero();
      ZState sz = ZState::Zero();
      for (int j = 0; j < p.total_stages(); ++j) {
        const double* d = &p.dense()[static_cast<std::size_t>(j * p.dense_degree())];
        double b = 0.0;
        for (int q = p.dense_degree() - 1; q >= 0; --q) b = (b + d[q]) * theta;
        su += b * frame_.K[static_cast<std::size_t>(j)];
        sz += b * frame_.L[static_cast<std::size_t>(j)];
      }
      FlatState y;
      set_rotation(y, map_.exp(Vec3(h * su)) * R_prev_);
      ++cost.exp_evals;
      y.tail<kZSize>() = z_prev_ + h * sz;
      dense_t_.push_back(out[m]);
      dense_y_.push_back(y);
    }
  }

  const Problem& problem_;
  const Tableau& tableau_;
  const StageTerms& terms_;
  Coordinates map_;
  bool anisotropic_;      // stage orientations needed
  RkmkStages& frame_;     // the pair's stages (and a fixed step's of any count)
  int fsal_;              // the FSAL stage, -1 without one
  bool fsal_in_attempt_;  // the error estimate uses it (BS32, DP54)
  // the pair's
  Tolerances tol_;
  const std::vector<double>* outputs_ = nullptr;
  FlatState y_, y_prev_;  // the state; before the step accepted last
  Mat3 R_, R_prev_;       // their R and z, as the stages read them
  ZState z_, z_prev_;
  Vec3 omega_first_, omega_fsal_;  // omega at the step's start; at the FSAL stage
  ZState g_first_;
  Vec3 u_new_, u_fsal_;  // the step tried last; the FSAL stage's U
  ZState dz_new_, dz_fsal_;
  std::size_t next_out_ = 0;
  std::vector<double> dense_t_;
  std::vector<FlatState> dense_y_;
};

}  // namespace rb

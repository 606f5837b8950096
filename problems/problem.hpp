#pragma once
// What every problem offers the integrators (docs/design.md): the flat view F(y),
// the Lie-group view (omega(R, z), G(R, z)), the start, the validity checks of
// docs/model.md ("Where the model stops holding") and an exact solution if known.
//
// A Problem is immutable and shared read-only by every run and thread; runs
// keep their own counters.
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "problems/invariants.hpp"
#include "problems/rolling_ball.hpp"
#include "problems/status.hpp"

namespace rb {

// [xmin, xmax] x [ymin, ymax]; leaving it ends a run. Unbounded by default.
struct Domain {
  double xmin = -std::numeric_limits<double>::infinity();
  double xmax = std::numeric_limits<double>::infinity();
  double ymin = -std::numeric_limits<double>::infinity();
  double ymax = std::numeric_limits<double>::infinity();
  bool contains(double x, double y) const { return x >= xmin && x <= xmax && y >= ymin && y <= ymax; }
};

// A closed-form solution at time t. The rotation is known only for some
// motions (a fixed rotation axis); has_rotation says whether R is exact.
struct ExactState {
  Vec2 alpha;
  Vec3 omega;
  Mat3 R = Mat3::Identity();
  bool has_rotation = false;
};

class ExactSolution {
 public:
  virtual ~ExactSolution() = default;
  // The name scenes use for it under "exact": "plane", "incline", ...
  virtual std::string name() const = 0;
  virtual ExactState at(double t) const = 0;
};

// Validity of a state, as a status (ok while the model holds).
struct Validity {
  Status status = Status::ok;
  std::string reason;  // a sentence with the numbers, empty when ok
};

class Problem {
  static constexpr double kHuge = std::numeric_limits<double>::infinity();

 public:
  Problem(std::string name, RollingBall model, FlatState y0, double t_end, Domain domain = {},
          std::shared_ptr<const ExactSolution> exact = nullptr,
          std::vector<std::shared_ptr<const FirstIntegrals>> invariants = {})
      : name_(std::move(name)),
        model_(std::move(model)),
        y0_(y0),
        t_end_(t_end),
        domain_(domain),
        exact_(std::move(exact)),
        invariants_(std::move(invariants)) {}

  const std::string& name() const { return name_; }
  const RollingBall& model() const { return model_; }
  const FlatState& y0() const { return y0_; }
  double t_end() const { return t_end_; }
  const Domain& domain() const { return domain_; }
  // nullptr when the scene has no closed form.
  const ExactSolution* exact() const { return exact_.get(); }
  // The first integrals beyond the energy the scene declares (checked on load).
  const std::vector<std::shared_ptr<const FirstIntegrals>>& invariants() const { return invariants_; }

  // The flat view: dy = F(y), 14 numbers each.
  template <class T>
  void flat_rhs(const T* y, T* dy) const {
    model_.flat_rhs(y, dy);
  }
  // The same, also giving the validity margins at y (no extra work but a
  // few products: the quantities come from the evaluation itself). Always
  // inlined, as the model's own, so that a stage loop keeps the evaluation
  // in registers (out of line: 23 instructions a call more, callgrind).
  [[gnu::always_inline]] void flat_rhs(const double* y, double* dy, ModelMargins& margins) const {
    model_.flat_rhs(y, dy, margins);
  }
  // The Lie-group view at orientation R: omega(R, z) and G(R, z), z and dz
  // 5 numbers, omega 3. R matters only where model().anisotropic().
  template <class T>
  void lie_rhs(const Mat3& R, const T* z, T* omega, T* dz) const {
    model_.lie_rhs(R, z, omega, dz);
  }
  [[gnu::always_inline]] void lie_rhs(const Mat3& R, const double* z, double* omega, double* dz,
                                      ModelMargins& margins) const {
    model_.lie_rhs(R, z, omega, dz, margins);
  }

  // Cheap check for every step: the state is finite and inside the domain.
  Validity check_step(const FlatState& y) const;
  // A test the drivers run at every step before check_step, inlined and
  // branch-free: true means check_step says ok. The sum of the entries is
  // finite when all are (NaN and infinities carry through it); a false
  // alarm (the sum of finite entries overflowing) costs a call of
  // check_step, which then clears the state.
  bool surely_within_step(const FlatState& y) const {
    const bool finite = std::abs(y.sum()) < kHuge;
    const bool inside = domain_.contains(y[kOffsetAlpha], y[kOffsetAlpha + 1]);
    return finite & inside;
  }
  // The model's own limits from the margins of an evaluation: lift-off
  // (F . N <= 0), curvature (r max kappa >= 1 or E singular), a non-finite
  // landscape.
  Validity check_model(const ModelMargins& margins) const;
  // Whether check_model says ok, as one branch-free test: the drivers ask
  // this every step and check_model only when it fails (for the reason, or
  // to clear a false alarm: margins all finite whose sum overflows). The
  // margins summed are all positive where the comparisons hold, so the sum
  // is finite exactly when they are; NaN fails every comparison.
  static bool within_model(const ModelMargins& m) {
    return m.regular() & (m.normal_force > 0.0) & (m.normal_force + m.det_E + m.fit_xx + m.fit_yy < kHuge);
  }

  // Every check of docs/model.md at one state: check_step, then check_model
  // from one evaluation at y (for states no stage evaluates).
  Validity check_full(const FlatState& y) const;

 private:
  std::string name_;
  RollingBall model_;
  FlatState y0_;
  double t_end_;
  Domain domain_;
  std::shared_ptr<const ExactSolution> exact_;
  std::vector<std::shared_ptr<const FirstIntegrals>> invariants_;
};

}  // namespace rb

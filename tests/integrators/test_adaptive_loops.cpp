// The estimating loop (integrators/adaptive_loops.hpp) with its controller
// as a value: the steps it takes are the given controller's decisions and
// nothing else's.
#include <gtest/gtest.h>

#include <vector>

#include "fixtures.hpp"
#include "integrators/adaptive_loops.hpp"

namespace rb {
namespace {

using testing::valley;

// The scripted error norm of a step of h: (h / 0.01)^2, an estimate of
// order 2 that meets the tolerance up to h = 0.01.
double scripted_error(double h) { return (h / 0.01) * (h / 0.01); }

// Explicit Euler on the flat view with the scripted error: every accept or
// reject, and every next step, is the controller's.
class ScriptedEuler {
 public:
  static constexpr bool dense_output = false;
  explicit ScriptedEuler(const Problem& problem) : problem_(problem), y_(problem.y0()) {}
  int error_order() const { return 2; }
  double try_step(double /*t*/, double h, Cost& cost) {
    FlatState f;
    stage_flat_rhs(problem_, y_.data(), f.data(), cost);
    ++cost.rhs_evals;
    trial_ = y_ + h * f;
    return scripted_error(h);
  }
  void accept(double /*t*/, double h, Cost& /*cost*/) {
    y_ = trial_;
    accepted.push_back(h);
  }
  void state(FlatState& y) const { y = y_; }
  void interpolate(double, FlatState&) const {}
  void restore(const FlatState& y) { y_ = y; }

  std::vector<double> accepted;  // the accepted steps, in order

 private:
  const Problem& problem_;
  FlatState y_, trial_;
};

// What the controller alone decides from h0 with the scripted error, on a
// run to t_end that lands on it (a step within min_step_at of t_end is
// stretched to it; the one landing step is h = t_end - t): the accepted
// steps, and the count of rejected ones.
struct Decided {
  std::vector<double> steps;
  long rejected = 0;
};
Decided decided_by(FilterController controller, double h0, double t_end) {
  Decided out;
  double t = 0.0, h = h0;
  for (;;) {
    const bool lands = t + h >= t_end - min_step_at(t_end);
    const double h_try = lands ? t_end - t : h;
    const StepDecision d = controller.decide(scripted_error(h_try), h_try);
    h = d.h_next;
    if (!d.accepted) {
      ++out.rejected;
      continue;
    }
    out.steps.push_back(h_try);
    if (lands) return out;
    t += h_try;
  }
}

TEST(AdaptiveLoops, EstimatingLoopTakesTheStepsItsControllerDecides) {
  const Problem& p = valley();
  RunOptions o;
  o.h = 0.05;  // first tried: rejected (error 25)
  o.t_end = 0.2;
  o.tolerances = Tolerances(1e-6, 1e-9);
  std::vector<std::vector<double>> runs;
  long rejected = 0;
  for (const char* name : {"i", "pi", "pid"}) {
    const FilterController controller(filter_controller(name), 2);
    ScriptedEuler stepper(p);
    const RunResult r = drive_estimating(p, o, 1, stepper, controller);
    const Decided want = decided_by(controller, o.h, o.t_end);
    ASSERT_EQ(r.status, Status::ok) << name << ": " << r.message;
    EXPECT_EQ(r.stop_time, o.t_end) << name;
    EXPECT_EQ(stepper.accepted, want.steps) << name;
    EXPECT_EQ(r.cost.steps, static_cast<long>(want.steps.size())) << name;
    EXPECT_EQ(r.cost.rejected, want.rejected) << name;
    rejected += r.cost.rejected;
    runs.push_back(stepper.accepted);
  }
  // each begins with a rejection: rejections are the controller's too
  EXPECT_GE(rejected, 3);
  // the three filters are three different step sequences
  EXPECT_NE(runs[0], runs[1]);
  EXPECT_NE(runs[1], runs[2]);
  EXPECT_NE(runs[0], runs[2]);
}

}  // namespace
}  // namespace rb

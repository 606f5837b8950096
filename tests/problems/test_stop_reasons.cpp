// Where the model stops holding (docs/model.md): scenes in tests/data built to end
// a run with each stop reason. Each loads (its start is valid), and an rkmk4
// run stops early with the right status, keeping the rows before the stop.
#include <gtest/gtest.h>

#include "integrators/registry.hpp"
#include "problems/scene.hpp"

namespace rb {
namespace {

// rkmk4 with h = 1e-3 and the full validity check every 0.01 (check_full
// runs at outputs only) on a scene from tests/data.
void expect_stop(const std::string& file, Status want) {
  SCOPED_TRACE(file);
  const Problem p = make_problem(load_scene(std::string(RB_TEST_DATA) + "/" + file));
  ASSERT_EQ(p.check_full(p.y0()).status, Status::ok) << "the start itself is valid";
  RunOptions o;
  o.h = 1e-3;
  for (int k = 1; k * 0.01 < p.t_end() - 1e-9; ++k) o.output_times.push_back(k * 0.01);
  const RunResult r = find_integrator("rkmk4").integrate(p, o);
  EXPECT_EQ(status_name(r.status), status_name(want)) << r.message;
  EXPECT_FALSE(r.message.empty());
  EXPECT_GT(r.stop_time, 0.0);
  EXPECT_LT(r.stop_time, p.t_end());
  // the rows before the stop are kept, valid, and end at or before the stop
  ASSERT_GE(r.output.t.size(), 10u);
  EXPECT_LE(r.output.t.back(), r.stop_time);
  EXPECT_TRUE(r.final_state.allFinite());
  for (const FlatState& y : r.output.y) EXPECT_EQ(p.check_full(y).status, Status::ok);
}

TEST(StopReason, LiftOffOverACrest) { expect_stop("stop-lift-off.json", Status::lift_off); }

TEST(StopReason, CurvatureInANarrowingValley) { expect_stop("stop-curvature.json", Status::curvature); }

TEST(StopReason, DomainWhenRollingOut) { expect_stop("stop-domain.json", Status::domain); }

TEST(StopReason, DivergedPastTheLandscapesEdge) { expect_stop("stop-nonfinite.json", Status::diverged); }

}  // namespace
}  // namespace rb

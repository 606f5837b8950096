// One measure of drift for the report, the stability study and `rollbench
// trajectory` (bench/lib/drift.hpp), against closed forms: scaling the
// momentum v by s scales the kinetic energy by s^2, and R scaled by (1 + e)
// has the defect ||(1 + e)^2 I - I||_F = sqrt(3) ((1 + e)^2 - 1).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bench/lib/drift.hpp"
#include "problems/scene.hpp"

namespace rb {
namespace {

TEST(Drift, EnergyAndRotationDefectAgainstClosedForms) {
  const Problem problem = make_problem(load_scene("plane"));
  const FlatState y0 = problem.y0();
  const Derived start = problem.model().derived(y0);
  const BallParams& b = problem.model().params();
  const double kinetic = start.energy - b.mass * b.gravity * start.centre.z();
  ASSERT_GT(kinetic, 0.0);

  const DriftMeter meter(problem);
  EXPECT_EQ(meter.at(y0).energy, 0.0);
  FlatState faster = y0;
  faster.segment<3>(kOffsetV) *= 1.1;
  EXPECT_NEAR(meter.at(faster).energy, (1.1 * 1.1 - 1.0) * kinetic, 1e-12 * kinetic);

  const double e = 1e-6;
  FlatState stretched = y0;
  set_rotation(stretched, (1.0 + e) * rotation_of(y0));
  const double defect = std::sqrt(3.0) * ((1.0 + e) * (1.0 + e) - 1.0);
  EXPECT_NEAR(meter.at(stretched).rotation_defect, defect, 1e-9 * defect);

  // the largest over the start and the outputs; a non-finite state does not raise it
  Trajectory run;
  run.push(0.5, faster);
  run.push(1.0, stretched);
  FlatState broken = y0;
  broken[0] = std::numeric_limits<double>::quiet_NaN();
  run.push(1.5, broken);
  const Drift largest = largest_drift(problem, run);
  EXPECT_EQ(largest.energy, meter.at(faster).energy);
  EXPECT_EQ(largest.rotation_defect, meter.at(stretched).rotation_defect);
  EXPECT_EQ(largest_drift(problem, Trajectory{}).rotation_defect, start.rotation_defect);
}

}  // namespace
}  // namespace rb

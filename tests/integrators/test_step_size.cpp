// The step h as a typed value (integrators/step_size.hpp): checked where it
// is set, so that no integrator is handed a step none could take.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/step_size.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

std::string refusal(double h) {
  try {
    RunOptions options;
    options.h = h;
    return "taken";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(StepSize, RefusesWhatNoMethodCanTake) {
  const std::string expected =
      "'h': the step h must be a finite number >= 0 (0: an adaptive method chooses its first step)";
  for (const double bad : {-1.0, -0.0 - 1e-300, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()})
    EXPECT_EQ(refusal(bad), expected) << bad;
  EXPECT_EQ(refusal(0.0), "taken");
  EXPECT_EQ(refusal(1e-300), "taken");
}

TEST(StepSize, KeepsTheNumberAndAFixedStepNeedsOne) {
  const StepSize h(0.125);
  EXPECT_EQ(static_cast<double>(h), 0.125);
  EXPECT_EQ(h.fixed_step(), 0.125);
  try {
    (void)StepSize().fixed_step();
    ADD_FAILURE() << "a fixed step of 0 was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "'h': a fixed-step method needs a step h > 0");
  }
}

}  // namespace
}  // namespace rb

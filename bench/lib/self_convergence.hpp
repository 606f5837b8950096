#pragma once
// Self-convergence: an order estimate that uses no reference. Two runs of
// one fixed-step method at h and h/2 end a distance D(h) = C (1 - 2^-p) h^p
// apart, so log D against log h has the method's slope p wherever the
// reference-based fit has it; where the two disagree, one of them does not
// measure the method (a reference too coarse, a plateau).
#include <array>
#include <vector>

#include "bench/lib/fit_run.hpp"

namespace rb {

// The distance in each error component between the end of a run and the
// end of its partner at half the step; h is the larger step.
struct SelfDifference {
  double h = kNaN;
  std::array<double, kErrorComponentCount> distance{};
};

// Every pair of runs of the group (one scene, one fixed-step method) at h
// and h/2 (within 1e-9 relative) that both reached the same end time, by h
// ascending.
std::vector<SelfDifference> self_differences(const std::vector<const FitRun*>& group);

}  // namespace rb

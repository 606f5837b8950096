#pragma once
// Ladders that reach the asymptotic range: after a sweep, every fixed-step
// method whose order fit on a scene is still pre-asymptotic (its halving
// slopes move and no point reached the plateau, bench/lib/order_fit.hpp),
// against the reference or by self-convergence, gets a run at half its
// smallest step; the sweep repeats this, round after round, until no fit
// wants finer steps, a run would take more than kMaxExtendedSteps (2^20:
// euler's omega on chaplygin-plane needs h = 2^-18, 786432 steps), or
// kMaxLadderExtensions rounds are done.
#include <vector>

#include "bench/lib/sweep.hpp"

namespace rb {

inline constexpr long kMaxExtendedSteps = 1L << 20;
inline constexpr int kMaxLadderExtensions = 8;

// The runs to add: one per (scene, fixed-step method) of records that wants
// finer steps and whose half step stays within kMaxExtendedSteps (and the
// spec's max_steps), in the order of the records; indices from next_index.
std::vector<SweepTask> finer_step_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                        const std::vector<RunRecord>& records, std::size_t next_index);

}  // namespace rb

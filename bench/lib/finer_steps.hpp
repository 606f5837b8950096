#pragma once
// Ladders that reach the asymptotic range: after a sweep, every fixed-step
// method whose order fit on a scene wants finer steps (pre-asymptotic,
// straddling or short of points, and no point on the plateau,
// bench/lib/order_fit.hpp), or has too few errors because its runs failed
// (failed_runs_want_finer_steps), gets a run at half its smallest step;
// the sweep repeats this, round after round, until no fit wants finer
// steps, a run would take more than kMaxExtendedSteps (2^20: euler's omega
// on chaplygin-plane needs h = 2^-18, 786432 steps), or
// kMaxLadderExtensions rounds are done.
#include <array>
#include <vector>

#include "bench/lib/group_orders.hpp"
#include "bench/lib/sweep.hpp"

namespace rb {

// A run that ended with this status leaves room for a finer step: it
// reached t_end, or it stopped on a limit of the scene that a smaller step
// may keep it from (diverged, lift-off, curvature, domain, chart-limit: an
// explicit method unstable at this step). Not a crash, a time-out, a
// library error, a step budget or R off SO(3).
bool finer_step_may_run(Status status);

// True when some component has too few errors because runs of the ladder
// failed (inconclusive_reason "failed runs") and none of its points reached
// the plateau, and the run at the smallest step (smallest_step: its status)
// leaves room for a finer step: euler on the Chaplygin scenes leaves the
// chart or the domain at every step of the default ladder, down to 2^-10,
// and converges below it.
bool failed_runs_want_finer_steps(const std::array<ComponentOrder, kErrorComponentCount>& orders, Status smallest_step);

inline constexpr long kMaxExtendedSteps = 1L << 20;
inline constexpr int kMaxLadderExtensions = 8;

// The runs to add: one per (scene, fixed-step method) of records that wants
// finer steps and whose half step stays within kMaxExtendedSteps (and the
// spec's max_steps), in the order of the records; indices from next_index.
std::vector<SweepTask> finer_step_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                        const std::vector<RunRecord>& records, std::size_t next_index);

}  // namespace rb

#pragma once
// The observed orders of one (scene, fixed-step method): per error
// component, the fit against the reference, the self-convergence fit
// (bench/lib/self_convergence.hpp) and the verdict both give. What the
// report's "orders" write and what decides whether a ladder is extended.
#include <array>
#include <vector>

#include "bench/lib/fit_run.hpp"
#include "bench/lib/order_fit.hpp"

namespace rb {

struct ComponentOrder {
  int declared = 0;
  OrderFit reference, self;
  OrderJudgement judgement;
};

// Up to this many points in a fit window: on the quarter-step ladder 6 span
// only 1.5 halvings.
inline constexpr std::size_t kOrderWindowPoints = 8;
// An error above this (a rotation angle or a length of the scene's unit
// size) has nothing left to converge.
inline constexpr double kOrderCeiling = 0.1;

// group: the runs of one scene and fixed-step method; floor: the scene's
// reference floor. A component below the floor (listed in below_floor)
// counts as on the plateau.
std::array<ComponentOrder, kErrorComponentCount> group_orders(const std::vector<const FitRun*>& group, double floor);

// True when some component's fit against the reference wants finer steps
// (order_fit.hpp): a finer step would decide. (The self-convergence fit
// has no floor: near rounding its slopes scatter, and finer steps would
// not settle them.)
bool wants_finer_steps(const std::array<ComponentOrder, kErrorComponentCount>& orders);

}  // namespace rb

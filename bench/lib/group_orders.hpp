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
// size) has nothing left to converge; for omega, kOrderCeiling x the
// reference's largest |omega| (order_ceiling).
inline constexpr double kOrderCeiling = 0.1;

// What a scene gives the fits of its runs: the reference's floor (its own
// error) and omega_scale (the reference's largest |omega|).
struct OrderScale {
  double floor = 0.0;
  double omega_scale = 1.0;
};

// The ceiling of component i (kErrorComponents): kOrderCeiling, times
// omega_scale for a component on that scale (an angular velocity's error
// of a tenth of the largest |omega|, as an angle's of 0.1 rad).
double order_ceiling(std::size_t component, double omega_scale);

// group: the runs of one scene and fixed-step method; scale: its scene's.
// A component below the floor (listed in below_floor) counts as on the
// plateau.
std::array<ComponentOrder, kErrorComponentCount> group_orders(const std::vector<const FitRun*>& group,
                                                              const OrderScale& scale);

// True when some component's fit against the reference wants finer steps
// (order_fit.hpp): a finer step would decide. (The self-convergence fit
// has no floor: near rounding its slopes scatter, and finer steps would
// not settle them.)
bool wants_finer_steps(const std::array<ComponentOrder, kErrorComponentCount>& orders);

}  // namespace rb

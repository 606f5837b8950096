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

// The step of the reference's finer solution (its cross-check takes half
// the primary's step, ReferenceSettings::h = 2^-10): the runs whose
// disagreement measured the floor, rounding included, took t_end /
// kReferenceRoundingStep steps (tests/bench/test_order_ladder_rules.cpp
// holds the two together).
inline constexpr double kReferenceRoundingStep = 1.0 / 2048.0;

// What a scene gives the fits of its runs: the reference's floor (its own
// error, the largest over the components), omega_scale (the reference's
// largest |omega|), the floor of each component (its own error in that
// component; NaN: floor stands for it, as in a report older than these;
// 0, a component the reference and its check agree on to the bit: floor
// stands for it too) and the step at which the floors measured the
// rounding (plateau_level, order_fit.hpp).
struct OrderScale {
  double floor = 0.0;
  double omega_scale = 1.0;
  std::array<double, kErrorComponentCount> component_floor{kNaN, kNaN, kNaN, kNaN};
  double rounding_step = kReferenceRoundingStep;
};

// The self-convergence fit (self_convergence.hpp) of distances D(h)
// between the runs at h and h/2: over the same steps as the reference
// fit's window (h in [h_min, h_max], within kWindowSlack), so that both
// slopes read the same stretch of the ladder and a pre-asymptotic step
// outside the window moves neither; where that holds fewer than two
// distances, or the reference fit has no slope, its own window from the
// smallest step up. A distance within kSelfPlateauMultiple x the rounding
// level (plateau_level(rounding, rounding_step, h): the reference's floor,
// as the reference fit's) is left out: no reference, but rounding.
inline constexpr double kWindowSlack = 1.1;
inline constexpr double kSelfPlateauMultiple = 10.0;
OrderFit self_convergence_fit(const std::vector<double>& h, const std::vector<double>& distance,
                              const OrderFit& reference, double ceiling, double rounding = 0.0,
                              double rounding_step = 0.0);

// A sweep's scene's: its reference's floors and omega_scale.
OrderScale order_scale(const SweepScene& scene);

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

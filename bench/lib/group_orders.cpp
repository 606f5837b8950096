#include "bench/lib/group_orders.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "bench/lib/self_convergence.hpp"

namespace rb {

OrderFit self_convergence_fit(const std::vector<double>& h, const std::vector<double>& distance,
                              const OrderFit& reference, double ceiling, double rounding, double rounding_step) {
  // no reference, so no floor: rounding alone ends the self-convergence,
  // at kSelfPlateauMultiple x its level
  const double floor = rounding * kSelfPlateauMultiple / kFloorMultiple;
  const OrderFit own = fit_order(h, distance, floor, ceiling, kOrderWindowPoints, rounding_step);
  if (!std::isfinite(reference.slope)) return own;
  std::vector<double> in_h, in_d;
  for (std::size_t k = 0; k < h.size() && k < distance.size(); ++k)
    if (h[k] >= reference.h_min / kWindowSlack && h[k] <= reference.h_max * kWindowSlack)
      in_h.push_back(h[k]), in_d.push_back(distance[k]);
  const OrderFit matched = fit_order(in_h, in_d, floor, ceiling, kOrderWindowPoints, rounding_step);
  return std::isfinite(matched.slope) ? matched : own;
}

OrderScale order_scale(const SweepScene& scene) {
  return {scene.reference.error, scene.omega_scale, scene.reference.component_error, kReferenceRoundingStep};
}

double order_ceiling(std::size_t component, double omega_scale) {
  return kErrorComponents[component].scale == ErrorScale::omega_scale ? kOrderCeiling * omega_scale : kOrderCeiling;
}

std::array<ComponentOrder, kErrorComponentCount> group_orders(const std::vector<const FitRun*>& group,
                                                              const OrderScale& scale) {
  std::array<ComponentOrder, kErrorComponentCount> out;
  if (group.empty()) return out;
  const FitRun& first = *group.front();
  const std::vector<SelfDifference> self = self_differences(group);
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    const std::string c = kErrorComponents[i].name;
    // a component whose reference and check agree to the bit (omega on the
    // plane, constant) measures no rounding: the reference's largest own error stands for it
    const double own = scale.component_floor[i];
    const double floor = std::isfinite(own) && own > 0.0 ? own : scale.floor;
    std::vector<double> h, e;
    for (const FitRun* r : group) {
      h.push_back(r->h);
      // below the floor: null in the report, the floor here (counted, never fitted)
      const std::vector<std::string>& below = r->error.below_floor;
      const bool at_floor = std::find(below.begin(), below.end(), c) != below.end();
      e.push_back(at_floor ? floor : r->error.component(i));
    }
    std::vector<double> self_h, self_d;
    for (const SelfDifference& d : self) self_h.push_back(d.h), self_d.push_back(d.distance[i]);
    ComponentOrder& o = out[i];
    // a higher order than declared is no failure: for odd-order flat-view
    // methods the leading error in R is symmetric, so the rotation angle
    // after projection converges one order faster
    o.declared = c == "rotation" ? first.declared_rotation_order : first.declared_order;
    const double ceiling = order_ceiling(i, scale.omega_scale);
    o.reference = fit_order(h, e, floor, ceiling, kOrderWindowPoints, scale.rounding_step);
    o.self = self_convergence_fit(self_h, self_d, o.reference, ceiling, floor, scale.rounding_step);
    o.judgement = judge_order(o.reference, o.self, o.declared);
  }
  return out;
}

bool wants_finer_steps(const std::array<ComponentOrder, kErrorComponentCount>& orders) {
  return std::any_of(orders.begin(), orders.end(),
                     [](const ComponentOrder& o) { return wants_finer_steps(o.reference, o.declared); });
}

}  // namespace rb

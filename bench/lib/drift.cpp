#include "bench/lib/drift.hpp"

#include <algorithm>
#include <cmath>

namespace rb {

DriftMeter::DriftMeter(const Problem& problem)
    : model_(&problem.model()), start_energy_(problem.model().derived(problem.y0()).energy) {}

Drift DriftMeter::at(const FlatState& y) const {
  const Derived d = model_->derived(y);
  return {std::abs(d.energy - start_energy_), d.rotation_defect};
}

double energy_scale(const Problem& problem) {
  const BallParams& b = problem.model().params();
  const Derived d = problem.model().derived(problem.y0());
  const double potential = b.mass * b.gravity * d.centre.z();
  return b.mass * b.gravity * b.radius + std::max(0.0, d.energy - potential);
}

Drift largest_drift(const Problem& problem, const Trajectory& output) {
  const DriftMeter meter(problem);
  Drift largest = meter.at(problem.y0());
  for (const FlatState& y : output.y) {
    const Drift d = meter.at(y);
    largest.energy = std::max(largest.energy, d.energy);
    largest.rotation_defect = std::max(largest.rotation_defect, d.rotation_defect);
  }
  return largest;
}

}  // namespace rb

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

InvariantMeter::InvariantMeter(const Problem& problem) : problem_(&problem) {
  for (const auto& family : problem.invariants())
    for (const std::string& q : family->quantities()) names_.push_back(family->name() + "." + q);
  std::vector<double> magnitudes;
  start_ = values(problem.y0(), &magnitudes);
  for (const double m : magnitudes) scale_.push_back(m > 0.0 ? m : 1.0);
}

std::vector<double> InvariantMeter::values(const FlatState& y, std::vector<double>* magnitudes) const {
  std::vector<double> v(names_.size()), m(names_.size());
  std::size_t at = 0;
  for (const auto& family : problem_->invariants()) {
    family->at(y, v.data() + at, m.data() + at);
    at += family->quantities().size();
  }
  if (magnitudes) *magnitudes = std::move(m);
  return v;
}

std::vector<double> InvariantMeter::errors(const FlatState& y) const {
  std::vector<double> e = values(y, nullptr);
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = std::abs(e[i] - start_[i]) / scale_[i];
  return e;
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

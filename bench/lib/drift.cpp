#include "bench/lib/drift.hpp"

#include <algorithm>
#include <cmath>

#include "problems/energy.hpp"

namespace rb {

DriftMeter::DriftMeter(const Problem& problem)
    : model_(&problem.model()),
      start_energy_(problem.model().derived(problem.y0()).energy),
      start_energy_on_group_(energy_on_group(problem.model(), problem.y0())) {}

Drift DriftMeter::at(const FlatState& y) const {
  const Derived d = model_->derived(y);
  const double flat = std::abs(d.energy - start_energy_);
  // H does not read R for the homogeneous ball: the two are one number there
  // (and no SVD is spent on it); the start's R is a rotation, so both start
  // from the same H(y0)
  const double on_group = model_->anisotropic() ? std::abs(energy_on_group(*model_, y) - start_energy_on_group_) : flat;
  return {flat, d.rotation_defect, on_group};
}

InvariantMeter::InvariantMeter(const Problem& problem) : problem_(&problem) {
  for (const auto& family : problem.invariants()) {
    for (const std::string& q : family->quantities()) names_.push_back(family->name() + "." + q);
    for (const IntegralKind k : family->kinds()) kinds_.push_back(k);
  }
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
    largest.energy_on_group = std::max(largest.energy_on_group, d.energy_on_group);
  }
  return largest;
}

}  // namespace rb

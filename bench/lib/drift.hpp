#pragma once
// The drift of a run, measured one way for the report, the stability study
// and `rollbench trajectory`: the energy error |H(y) - H(y0)| against the
// problem's start and the rotation defect ||R^T R - I||_F (docs/model.md,
// invariants).
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

struct Drift {
  double energy = 0.0;           // |H(y) - H(y0)|, in the scene's energy units
  double rotation_defect = 0.0;  // ||R^T R - I||_F
};

// The drift of states of one problem against its start.
class DriftMeter {
 public:
  explicit DriftMeter(const Problem& problem);
  Drift at(const FlatState& y) const;

 private:
  const RollingBall* model_;
  double start_energy_;
};

// The errors of the first integrals a problem's scene declares
// (docs/model.md, "Invariants beyond the energy"), relative: |I(y) - I(y0)|
// over I's magnitude at the start (the sum of its terms' absolute values;
// 1 where that is 0, a start at rest).
class InvariantMeter {
 public:
  explicit InvariantMeter(const Problem& problem);
  // "routh-paraboloid.J1", ..., in the order of errors()
  const std::vector<std::string>& names() const { return names_; }
  std::vector<double> errors(const FlatState& y) const;

 private:
  std::vector<double> values(const FlatState& y, std::vector<double>* magnitudes) const;
  const Problem* problem_;
  std::vector<std::string> names_;
  std::vector<double> start_, scale_;
};

// The scene's energy scale: m g0 r plus the kinetic energy it starts with,
// so that a spinning start on flat ground is not judged on m g0 r alone
// (the stability study's bound and the horizon study's rounding level).
double energy_scale(const Problem& problem);

// The largest of each over the start and every recorded output of a run
// (a non-finite value does not raise it).
Drift largest_drift(const Problem& problem, const Trajectory& output);

}  // namespace rb

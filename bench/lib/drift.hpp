#pragma once
// The drift of a run, measured one way for the report, the stability study
// and `rollbench trajectory`: the energy error |H(y) - H(y0)| against the
// problem's start and the rotation defect ||R^T R - I||_F (docs/model.md,
// invariants).
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "problems/invariants.hpp"

namespace rb {

struct Drift {
  double energy = 0.0;           // |H(y) - H(y0)|, in the scene's energy units (H read on the flat view)
  double rotation_defect = 0.0;  // ||R^T R - I||_F
  // the same at the nearest rotation, |H(polar(R), v, alpha) - H(y0)|
  // (problems/energy.hpp): what the flat H hides where R drifts off SO(3)
  // for a ball whose orientation matters; equal to energy for the
  // homogeneous ball
  double energy_on_group = 0.0;
};

// The drift of states of one problem against its start.
class DriftMeter {
 public:
  explicit DriftMeter(const Problem& problem);
  Drift at(const FlatState& y) const;

 private:
  const RollingBall* model_;
  double start_energy_, start_energy_on_group_;
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
  // each one's kind (problems/invariants.hpp), in the same order
  const std::vector<IntegralKind>& kinds() const { return kinds_; }
  std::vector<double> errors(const FlatState& y) const;

 private:
  std::vector<double> values(const FlatState& y, std::vector<double>* magnitudes) const;
  const Problem* problem_;
  std::vector<std::string> names_;
  std::vector<IntegralKind> kinds_;
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

#pragma once
// The stability study's verdict on one rung (docs/usage.md, "Stability"): a
// run at h is unstable when it fails, never because it is inaccurate. It
// fails when it stops (diverged, chart-limit, domain, ...), when its energy
// error passes a stated fraction of the energy scale, when R leaves SO(3)
// by more than a stated O(1) amount, or when either grows exponentially
// rather than polynomially over the run. The accuracy at h (the largest
// energy error and rotation defect) is reported beside the verdict.
#include <string>
#include <vector>

#include "bench/lib/presets.hpp"
#include "bench/lib/sweep.hpp"  // kNaN

namespace rb {

// The shape of a series over the run [0, horizon]: its largest value in
// the windows (T/8, T/4], (T/4, T/2] and (T/2, T] and the power-law slopes
// between them, log2 of the ratio of successive maxima.
struct GrowthShape {
  double p_early = kNaN;  // (T/8, T/4] -> (T/4, T/2]; NaN where a window is empty or not > 0
  double p_late = kNaN;   // (T/4, T/2] -> (T/2, T]
  bool exponential = false;
};

GrowthShape growth_shape(const std::vector<double>& t, const std::vector<double>& value, double horizon,
                         const StabilityBounds& bounds);

// Why a rung failed: none (stable), stopped (a status other than ok),
// energy, rotation-defect, energy-growth, defect-growth (exponential).
enum class StabilityFailure { none, stopped, energy, rotation_defect, energy_growth, defect_growth };
const char* failure_name(StabilityFailure f);

struct RungVerdict {
  double energy_error = kNaN;     // max |H - H0| / energy scale over the recorded states; NaN when none is finite
  double rotation_defect = kNaN;  // max ||R^T R - I||_F over them
  GrowthShape energy_growth, defect_growth;
  StabilityFailure failure = StabilityFailure::none;
};

// The verdict on a run of status `status` with the relative energy error
// and rotation defect at times t (the recorded states up to its stop).
RungVerdict judge_rung(Status status, const std::vector<double>& t, const std::vector<double>& energy_error,
                       const std::vector<double>& rotation_defect, double horizon, const StabilityBounds& bounds);

}  // namespace rb

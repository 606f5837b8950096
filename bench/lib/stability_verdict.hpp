#pragma once
// The stability study's verdict on one rung at one horizon T (docs/usage.md,
// "Stability"), from the states its run recorded up to T. Two questions,
// kept apart:
// - did it blow up? It failed (stopped: a non-finite state, the solver
//   failing, or a physical stop, which on the study's bounded scenes only
//   the numerics cause; or a drift quantity passed its blow-up bound, where
//   no bounded motion goes) while every drift quantity was still within its
//   bound, or within blow_up_steps steps of the first leaving it: an error
//   that grows from the drift bound to the blow-up bound that fast is
//   multiplied by at least 20^(1/10) a step, exponential growth that is the
//   step's own. A run that drifts out of its bounds first and fails later
//   (its energy drifted until the ball left the scene) failed of its drift:
//   it is drift-limited, and the blow-up step stays where the step itself
//   breaks the run, at any horizon;
// - did it keep every drift bound (the energy error at the nearest
//   rotation, the rotation defect)? The largest step that does to T is the
//   drift-limited step h*(T), which moves with T where the drift grows as
//   a power of t.
#include <string>
#include <vector>

#include "bench/lib/presets.hpp"
#include "bench/lib/sweep.hpp"  // kNaN

namespace rb {

// The shape of a series over the run [0, horizon]: its largest value in
// the windows (T/8, T/4], (T/4, T/2] and (T/2, T] and the power-law slopes
// between them, log2 of the ratio of successive maxima; reported beside the
// verdict (how the drift grows), not read by it.
struct GrowthShape {
  double p_early = kNaN;  // (T/8, T/4] -> (T/4, T/2]; NaN where a window is empty or not > 0
  double p_late = kNaN;   // (T/4, T/2] -> (T/2, T]
  bool exponential = false;
};

GrowthShape growth_shape(const std::vector<double>& t, const std::vector<double>& value, double horizon,
                         const StabilityBounds& bounds);

// How a run blew up by a horizon (none: it did not): stopped (a status
// other than ok), energy-blow-up and defect-blow-up (past the blow-up
// bound), each before the run drifted out of its bounds (see above).
enum class BlowUp { none, stopped, energy, rotation_defect };
const char* blow_up_name(BlowUp b);

// The drift quantities with a bound: "energy" (max |H - H0| / the energy
// scale, H at the nearest rotation) and "rotation-defect" (max ||R^T R - I||_F).
inline constexpr const char* kEnergyQuantity = "energy";
inline constexpr const char* kDefectQuantity = "rotation-defect";

// The states of one run up to its stop: times, the relative energy error
// at the nearest rotation (what the bound reads), the flat one (beside it)
// and the rotation defect.
struct DriftSeries {
  std::vector<double> t, energy, energy_flat, defect;
};

struct HorizonVerdict {
  double horizon = 0.0;        // T: the states up to it were judged
  double crossed_at = kNaN;    // the first state past a drift bound, up to T (NaN: none)
  double failed_at = kNaN;     // the stop or the first state past a blow-up bound, up to T (NaN: none)
  double energy_error = kNaN;  // max relative energy error at the nearest rotation up to T; NaN when none is finite
  double energy_error_flat = kNaN;  // the same with the flat H (beside it)
  double rotation_defect = kNaN;    // max ||R^T R - I||_F up to T
  GrowthShape energy_growth, defect_growth;
  BlowUp blow_up = BlowUp::none;
  // the drift bounds kept up to T (a non-finite value passes every bound)
  bool energy_within = true, defect_within = true;
  bool within() const { return blow_up == BlowUp::none && energy_within && defect_within; }
};

// The verdict at T on a run of fixed step `step` that stopped before T
// (stopped_by: its last state is where it stopped) or not, from the states
// of s with t <= T.
HorizonVerdict judge_horizon(bool stopped_by, const DriftSeries& s, double horizon, double step,
                             const StabilityBounds& bounds);

// The time of the first state whose value passes bound (or is not
// finite); NaN when none does.
double first_past(const std::vector<double>& t, const std::vector<double>& value, double bound);

}  // namespace rb

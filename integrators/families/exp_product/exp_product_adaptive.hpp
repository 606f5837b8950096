#pragma once
// The adaptive stepper of an exponential-product scheme with an embedded
// update (ExpProductScheme::embedded; registry lines reach it through
// exp_product_method, exp_product.hpp): both updates are products over the same stages; the
// scheme's update propagates, the embedded one only measures the error.
//
// - The local error: for R the rotation vector of R_high R_low^T, taken as
//   vee of its skew part (sin(angle) axis: equal to O(angle^3), and the
//   angle is the error's size), against atol + rtol (R's entries are of
//   size 1, as a flat method sees them); for z componentwise against
//   atol + rtol max(|z_n,i|, |z_n+1,i|). Norm: root mean square over the
//   3 + 5 components, as the RKMK pairs (munthe_kaas_adaptive.hpp).
// - The step size comes from a controller (integrators/controllers/): by
//   default the PI, RunOptions::controller chooses another.
// - No dense output: steps are clamped to land on every output time.
//
// Cost per attempt: (stages - 1) rhs evaluations (the first stage once per
// accepted step), the stage exponentials on an anisotropic ball, and the
// exponentials of both updates.
#include <memory>
#include <string>

#include "integrators/families/exp_product/exp_product_scheme.hpp"
#include "integrators/integrator.hpp"

namespace rb {

// The scheme's adaptive integrator (its name; family the scheme's +
// "-adaptive"; controller, a filter, by default). Throws
// std::invalid_argument for a scheme without an embedded update or a
// malformed one, InputError for an unknown controller.
std::unique_ptr<Integrator> exp_product_adaptive(ExpProductScheme scheme, const std::string& controller = "pi");

}  // namespace rb

#pragma once
// The integrators of the exponential-product schemes (exp_product_scheme.hpp:
// the commutator-free and Crouch-Grossman methods), at fixed steps and on
// their embedded pairs, both with the one stepper of exp_product_stepper.hpp.
// A registry line names the scheme, the method and the controller, as
// rkmk_method does a tableau's:
//   exp_product_method(methods::cf4(), "cf4", kConstantController)
//   exp_product_method(methods::cg3_pair(), "cg3-adaptive", "pi")
#include <memory>
#include <string>

#include "integrators/families/exp_product/exp_product_scheme.hpp"
#include "integrators/integrator.hpp"

namespace rb {

// The scheme's integrator under name: fixed steps for "constant" (family the
// scheme's, "cf" or "cg"; the stages the update reads only), else adaptive
// on its embedded update with that filter controller by default (family the
// scheme's + "-adaptive"; every stage, steps clamped onto the outputs). Throws
// std::invalid_argument for a malformed scheme (a stage using a field not
// yet computed, ...) or an adaptive one without an embedded update, and
// InputError for an unknown controller.
std::unique_ptr<Integrator> exp_product_method(ExpProductScheme scheme, std::string name,
                                               const std::string& controller);

// so(3) exponentials a fixed step of the scheme computes (over the stages
// its update reads): with stage orientations (an anisotropic ball) or only
// the update's (a homogeneous ball, where R enters neither omega nor G)
int exponentials_per_step(const ExpProductScheme& scheme, bool anisotropic);

}  // namespace rb

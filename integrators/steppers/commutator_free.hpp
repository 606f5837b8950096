#pragma once
// The commutator-free Lie group method CF4 (integrators/steppers/exp_product.hpp).
#include "integrators/steppers/exp_product.hpp"

namespace rb::schemes {

ExpProductScheme cf4();

}  // namespace rb::schemes

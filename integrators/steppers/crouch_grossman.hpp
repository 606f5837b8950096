#pragma once
// Crouch-Grossman methods (integrators/steppers/exp_product.hpp): stage i's
// orientation is exp(a_{i,i-1} F_{i-1}) ... exp(a_{i,1} F_1) R_n and
// R_{n+1} = exp(b_s F_s) ... exp(b_1 F_1) R_n, F_1 acting first.
#include "integrators/steppers/exp_product.hpp"

namespace rb::schemes {

ExpProductScheme cg3();
// cg3 with an embedded order-2 update, for cg3-adaptive
ExpProductScheme cg3_pair();
ExpProductScheme cg4a();

}  // namespace rb::schemes

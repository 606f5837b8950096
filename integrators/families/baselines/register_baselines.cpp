// The practitioners' fixes of a flat method's rotation: rk4 projected back
// onto SO(3) after each step, and rk4 on a unit quaternion.
#include "integrators/families/baselines/baselines.hpp"
#include "integrators/families/families.hpp"

namespace rb {

void register_baselines(MethodList& list) {
  list.push_back(rk4_projected("rk4-projected", Projection::newton_schulz));
  list.push_back(rk4_projected("rk4-projected-svd", Projection::svd));
  list.push_back(rk4_quaternion("rk4-quaternion"));
}

}  // namespace rb

// The practitioners' fixes of a flat method's rotation: rk4 projected back
// onto SO(3) after each step, and rk4 on a unit quaternion.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/baselines/baselines.hpp"
#include "integrators/families/families.hpp"

namespace rb {

void register_baselines(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md).
  const std::string constant = kConstantController;
  list.push_back(rk4_baseline(RotationFix::project_newton_schulz, "rk4-projected", constant));
  list.push_back(rk4_baseline(RotationFix::project_svd, "rk4-projected-svd", constant));
  list.push_back(rk4_baseline(RotationFix::unit_quaternion, "rk4-quaternion", constant));
}

}  // namespace rb

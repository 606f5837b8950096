// Classical explicit Runge-Kutta on the flat view: fixed steps (family rk)
// and the embedded pairs (rk-adaptive), the flat twins of the RKMK pairs.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/families.hpp"
#include "integrators/families/rk/explicit_midpoint.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/methods/verner76.hpp"
#include "integrators/methods/verner98.hpp"
#include "integrators/steppers/tableau_methods.hpp"

namespace rb {

void register_rk(MethodList& list) {
  // One line a method: <way of stepping>(<method data>, "<name>", <controller>)
  // (docs/extending.md); the tableaux are in integrators/methods/.
  namespace m = methods;
  const std::string constant = kConstantController, pi = "pi";
  list.push_back(rk_method(m::euler(), "euler", constant));
  list.push_back(rk_method(m::heun(), "heun", constant));
  list.push_back(rk_method(m::kutta3(), "rk3", constant));
  list.push_back(rk_method(m::rk4(), "rk4", constant));
  list.push_back(rk_method(m::rk38(), "rk38", constant));
  list.push_back(explicit_midpoint("midpoint", constant));  // docs/extending.md's worked example
  // the flat twins of the RKMK pairs: the same embedded pair, PI controller
  // and RMS error norm, on the flat view (dp853's stretched estimate has no
  // flat twin)
  list.push_back(rk_method(m::bogacki_shampine32(), "rk-bs32-adaptive", pi));
  list.push_back(rk_method(m::dormand_prince54(), "rk-dp54-adaptive", pi));
  list.push_back(rk_method(m::fehlberg78(), "rk-f78-adaptive", pi));
  list.push_back(rk_method(m::verner76(), "rk-verner7-adaptive", pi));
  list.push_back(rk_method(m::verner98(), "rk-verner9-adaptive", pi));
}

}  // namespace rb

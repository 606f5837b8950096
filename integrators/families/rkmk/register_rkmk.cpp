// Lie-group Runge-Kutta: exp-Euler and Runge-Kutta-Munthe-Kaas at fixed steps
// (family rkmk; the dexpinv variants and the Cayley map among them) and on
// embedded pairs (rkmk-adaptive): what order buys, and what adaptivity buys.
#include "integrators/controllers/controller.hpp"
#include "integrators/families/families.hpp"
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/methods/verner76.hpp"
#include "integrators/methods/verner98.hpp"
#include "integrators/steppers/tableau_methods.hpp"

namespace rb {

void register_rkmk(MethodList& list) {
  using D = DexpinvKind;
  namespace m = methods;
  const std::string constant = kConstantController, pi = "pi";
  list.push_back(rkmk_method(m::euler(), "exp-euler", constant));
  list.push_back(rkmk_method(m::heun(), "rkmk2", constant));
  list.push_back(rkmk_method(m::kutta3(), "rkmk3", constant));
  list.push_back(rkmk_method(m::rk4(), "rkmk4", constant));
  list.push_back(rkmk_method(m::rk4(), "rkmk4-series", constant, D::truncated));
  list.push_back(rkmk_method(m::rk4(), "rkmk4-seminar", constant, D::seminar));
  list.push_back(rkmk_method(m::dormand_prince54(), "rkmk5", constant));
  list.push_back(rkmk_method(m::fehlberg78(), "rkmk8", constant));
  list.push_back(rkmk_method(m::bogacki_shampine32(), "rkmk-bs32-adaptive", pi));
  list.push_back(rkmk_method(m::dormand_prince54(), "rkmk-dp54-adaptive", pi));
  list.push_back(rkmk_method(m::dormand_prince853(), "rkmk-dp853-adaptive", pi));
  list.push_back(rkmk_method(m::fehlberg78(), "rkmk-f78-adaptive", pi));
  list.push_back(rkmk_method(m::verner76(), "rkmk-verner7-adaptive", pi));
  list.push_back(rkmk_method(m::verner98(), "rkmk-verner9-adaptive", pi));
  list.push_back(rkmk_cayley_method(m::rk4(), "rkmk4-cayley", constant));
}

}  // namespace rb

#include "integrators/tableau_twins.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/euler.hpp"
#include "integrators/methods/fehlberg78.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/methods/verner76.hpp"
#include "integrators/methods/verner98.hpp"

namespace rb {
namespace {

bool close(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(std::abs(x[i] - y[i]) <= kTwinTolerance)) return false;
  return true;
}

// the propagated method's coefficients: its first stages() stages
struct Propagated {
  std::vector<double> a, b, c;
};

Propagated propagated(const Tableau& t) {
  Propagated p;
  const int s = t.stages();
  for (int i = 0; i < s; ++i) {
    p.b.push_back(t.b(i));
    p.c.push_back(t.c(i));
    for (int j = 0; j < s; ++j) p.a.push_back(t.a(i, j));
  }
  return p;
}

}  // namespace

std::optional<std::string> shipped_twin(const Tableau& tableau) {
  namespace m = methods;
  // the flat integrator each shipped tableau is registered as (integrators/families/rk/register_rk.cpp)
  const std::vector<std::pair<std::string, Tableau>> shipped = {
      {"euler", m::euler()},
      {"heun", m::heun()},
      {"rk3", m::kutta3()},
      {"rk4", m::rk4()},
      {"rk38", m::rk38()},
      {"rk-bs32-adaptive", m::bogacki_shampine32()},
      {"rk-dp54-adaptive", m::dormand_prince54()},
      {"rkmk-dp853-adaptive", m::dormand_prince853()},
      {"rk-f78-adaptive", m::fehlberg78()},
      {"rk-verner7-adaptive", m::verner76()},
      {"rk-verner9-adaptive", m::verner98()},
  };
  const Propagated mine = propagated(tableau);
  for (const auto& [name, t] : shipped) {
    const Propagated theirs = propagated(t);
    if (close(mine.a, theirs.a) && close(mine.b, theirs.b) && close(mine.c, theirs.c))
      return "the shipped tableau '" + t.name() + "' (" + t.source() + "; built in as " + name + ")";
  }
  return std::nullopt;
}

}  // namespace rb

#include "integrators/runge_kutta.hpp"

#include <array>

#include "integrators/fixed_step.hpp"

namespace rb {

RungeKutta::RungeKutta(Tableau tableau, std::string name)
    : tableau_(std::move(tableau)), name_(name.empty() ? tableau_.name() : std::move(name)) {}

std::string RungeKutta::description() const {
  return "classical explicit RK (" + tableau_.name() + " tableau, " + std::to_string(tableau_.stages()) +
         " stages) on the flat view";
}

RunResult RungeKutta::integrate(const Problem& problem, const RunOptions& options) const {
  const Tableau& tab = tableau_;
  const int s = tab.stages();
  std::array<FlatState, kMaxStages> k;
  auto step = [&](FlatState& y, double /*t*/, double h, Cost& cost) {
    for (int i = 0; i < s; ++i) {
      FlatState Y = y;
      for (int j = 0; j < i; ++j)
        if (tab.a(i, j) != 0.0) Y += (h * tab.a(i, j)) * k[j];
      problem.flat_rhs(Y.data(), k[i].data());
    }
    for (int i = 0; i < s; ++i)
      if (tab.b(i) != 0.0) y += (h * tab.b(i)) * k[i];
    cost.rhs_evals += s;
  };
  return drive_fixed_step(problem, options, step);
}

}  // namespace rb

#pragma once
// Classical explicit Runge-Kutta on the flat view y in R^14, for any
// tableau: the seminar's method. R drifts off SO(3).
#include <memory>

#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"

namespace rb {

class RungeKutta final : public Integrator {
 public:
  // name defaults to the tableau's name.
  explicit RungeKutta(Tableau tableau, std::string name = {});
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

  const Tableau& tableau() const { return tableau_; }

 private:
  Tableau tableau_;
};

}  // namespace rb

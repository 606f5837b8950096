#pragma once
// Adaptive explicit Runge-Kutta on the flat view y in R^14 with an embedded
// pair: the flat counterpart of MuntheKaasAdaptive, with the same controller
// and the same kind of error norm, so that flat and Lie-group adaptivity
// compare on equal terms. R drifts off SO(3).
//
// - Local error h sum_i e_i k_i, each component against
//   atol + rtol max(|y_n,i|, |y_n+1,i|); norm: root mean square (Hairer's).
// - The step size comes from the shared controllers
//   (integrators/controllers/): Gustafsson's PI by default, as for
//   MuntheKaasAdaptive; RunOptions::controller chooses another.
// - No dense output: steps are clamped to land on every output time.
// - FSAL where the tableau's error weights use its FSAL stage: the stage at
//   (t + h, y_new) starts the next step; otherwise F(y_new) is evaluated
//   after acceptance.
#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"

namespace rb {

class RungeKuttaAdaptive final : public Integrator {
 public:
  // Throws InputError for a tableau without embedded weights (or with a
  // stretched estimate, which only the Lie pairs combine).
  RungeKuttaAdaptive(Tableau tableau, std::string name);
  std::string name() const override { return name_; }
  std::string family() const override { return "rk-adaptive"; }
  int declared_order() const override { return tableau_.order(); }
  bool adaptive() const override { return true; }
  std::string controller() const override { return "pi"; }
  std::string description() const override;
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

  const Tableau& tableau() const { return tableau_; }

 private:
  Tableau tableau_;
  std::string name_;
};

}  // namespace rb

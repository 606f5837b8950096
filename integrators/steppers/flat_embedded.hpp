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
// - FSAL where the pair has it (fsal < stages): the stage at (t + h, y_new)
//   starts the next step; otherwise F(y_new) is evaluated after acceptance.
#include "integrators/integrator.hpp"
#include "integrators/tableaus_high_order.hpp"

namespace rb {

class RungeKuttaAdaptive final : public Integrator {
 public:
  // Throws InputError for a pair whose sizes do not fit or whose b fails the
  // order conditions of its order.
  RungeKuttaAdaptive(EmbeddedPair pair, std::string name);
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

  const EmbeddedPair& pair() const { return pair_; }

 private:
  EmbeddedPair pair_;
};

}  // namespace rb

#pragma once
// Runge-Kutta-Munthe-Kaas on the Lie-group view (docs/model.md, "The methods compared"): over a
// step with R_n fixed, integrate u' = dexpinv_u(omega(z)), u(t_n) = 0,
// together with z' = G(z) by an explicit tableau, then
// R_{n+1} = exp(hat(u_{n+1})) R_n. R stays in SO(3) to rounding error.
// With the Euler tableau this is exp-Euler (Lie-Euler).
#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"
#include "problems/so3.hpp"

namespace rb {

class MuntheKaas final : public Integrator {
 public:
  MuntheKaas(Tableau tableau, std::string name, DexpinvKind dexpinv = DexpinvKind::exact);
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

  const Tableau& tableau() const { return tableau_; }
  DexpinvKind dexpinv_kind() const { return dexpinv_; }

 private:
  Tableau tableau_;
  DexpinvKind dexpinv_;
};

}  // namespace rb

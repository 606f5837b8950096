#pragma once
// Runge-Kutta-Munthe-Kaas with the Cayley map as its coordinates on SO(3):
// over a step with R_n fixed, u' = dcayinv_u(omega), u(t_n) = 0, together
// with z' = G, then R_{n+1} = cay(u_{n+1}) R_n (integrators/cayley.hpp).
// A coordinate map with phi(0) = I and dphi_0 = id changes only the
// coordinates of RKMK, not its order: with RK4 it stays order 4.
#include "integrators/integrator.hpp"
#include "integrators/tableau.hpp"

namespace rb {

class MuntheKaasCayley final : public Integrator {
 public:
  MuntheKaasCayley(Tableau tableau, std::string name);
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

 private:
  Tableau tableau_;
};

}  // namespace rb

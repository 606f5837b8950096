#include "integrators/steppers/rkmk_cayley.hpp"

#include <array>

#include "integrators/steppers/rkmk_step.hpp"

namespace rb {

MuntheKaasCayley::MuntheKaasCayley(Tableau tableau, std::string name)
    : Integrator({.name = std::move(name),
                  .family = "rkmk",
                  .declared_order = tableau.order(),
                  .description = "Runge-Kutta-Munthe-Kaas (" + tableau.name() +
                                 " tableau) with the Cayley map for coordinates; cayley maps counted as exp, "
                                 "dcayinv as dexpinv",
                  .on_group = true}),
      tableau_(std::move(tableau)) {}

RunResult MuntheKaasCayley::integrate(const Problem& problem, const RunOptions& options) const {
  const StageTerms terms(tableau_);
  std::array<Vec3, kMaxStages> K;
  std::array<ZState, kMaxStages> L;
  return drive_fixed_step(problem, options, MkStep<0, CayleyCoordinates>{problem, terms, {}, problem.model().anisotropic(), K, L});
}

}  // namespace rb

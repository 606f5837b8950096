#include "integrators/steppers/munthe_kaas.hpp"

#include <array>

#include "integrators/fixed_step.hpp"
#include "integrators/steppers/rkmk_step.hpp"

namespace rb {

MuntheKaas::MuntheKaas(Tableau tableau, std::string name, DexpinvKind dexpinv)
    : tableau_(std::move(tableau)), name_(std::move(name)), dexpinv_(dexpinv) {}

std::string MuntheKaas::description() const {
  const char* kind = dexpinv_ == DexpinvKind::exact       ? "closed-form dexpinv"
                     : dexpinv_ == DexpinvKind::truncated ? "dexpinv series to u x (u x w) / 12"
                                                          : "the seminar's dexpinv with its sign error";
  return "Runge-Kutta-Munthe-Kaas (" + tableau_.name() + " tableau, " + kind + ") on the Lie-group view";
}

RunResult MuntheKaas::integrate(const Problem& problem, const RunOptions& options) const {
  const StageTerms terms(tableau_);
  std::array<Vec3, kMaxStages> K;
  std::array<ZState, kMaxStages> L;
  const bool aniso = problem.model().anisotropic();
  switch (terms.stages) {
    case 1: return drive_fixed_step(problem, options, MkStep<1, ExpCoordinates>{problem, terms, {dexpinv_}, aniso, K, L});
    case 2: return drive_fixed_step(problem, options, MkStep<2, ExpCoordinates>{problem, terms, {dexpinv_}, aniso, K, L});
    case 3: return drive_fixed_step(problem, options, MkStep<3, ExpCoordinates>{problem, terms, {dexpinv_}, aniso, K, L});
    case 4: return drive_fixed_step(problem, options, MkStep<4, ExpCoordinates>{problem, terms, {dexpinv_}, aniso, K, L});
    default: return drive_fixed_step(problem, options, MkStep<0, ExpCoordinates>{problem, terms, {dexpinv_}, aniso, K, L});
  }
}

}  // namespace rb

#include "integrators/steppers/munthe_kaas.hpp"

#include <algorithm>
#include <array>

#include "integrators/fixed_step.hpp"
#include "integrators/steppers/rkmk_step.hpp"

namespace rb {

namespace {

MethodInfo facts_of(const Tableau& tableau, std::string name, DexpinvKind dexpinv) {
  const char* kind = dexpinv == DexpinvKind::exact       ? "closed-form dexpinv"
                     : dexpinv == DexpinvKind::truncated ? "dexpinv series to u x (u x w) / 12"
                                                         : "the seminar's dexpinv with its sign error";
  // The seminar's sign error costs an order in R; the declared order is the
  // tableau's (what the method claims), and the tests expose the loss. With
  // the seminar's sign the error in dexpinv is u x (u x w) / 6; since
  // u ~ c h w + O(h^2) at the stages, that is O(h^3), so the local error in u
  // is O(h^4) and R converges with order 3 (at most).
  return {.name = std::move(name),
          .family = "rkmk",
          .declared_order = tableau.order(),
          .rotation_order = dexpinv == DexpinvKind::seminar ? std::min(3, tableau.order()) : tableau.order(),
          .description = "Runge-Kutta-Munthe-Kaas (" + tableau.name() + " tableau, " + kind + ") on the Lie-group view",
          // another dexpinv is a variant, not the Lie-group version of the tableau
          .tableau = dexpinv == DexpinvKind::exact ? tableau.name() : std::string(),
          .on_group = true};
}

}  // namespace

MuntheKaas::MuntheKaas(Tableau tableau, std::string name, DexpinvKind dexpinv)
    : Integrator(facts_of(tableau, std::move(name), dexpinv)), tableau_(std::move(tableau)), dexpinv_(dexpinv) {}

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

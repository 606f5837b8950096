#include "integrators/families/rkmk/munthe_kaas.hpp"

#include <algorithm>
#include <array>

#include "integrators/families/rkmk/rkmk_step.hpp"
#include "integrators/steppers/stepped_method.hpp"

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

std::unique_ptr<Integrator> rkmk_fixed(Tableau tableau, std::string name, DexpinvKind dexpinv) {
  MethodInfo info = facts_of(tableau, std::move(name), dexpinv);
  return stepped_method(std::move(info), [tableau = std::move(tableau), dexpinv](const Problem& problem, auto&& drive) {
    const StageTerms terms(tableau);
    std::array<Vec3, kMaxStages> K;
    std::array<ZState, kMaxStages> L;
    const bool aniso = problem.model().anisotropic();
    switch (terms.stages) {
      case 1: return drive(MkStep<1, ExpCoordinates>{problem, terms, {dexpinv}, aniso, K, L});
      case 2: return drive(MkStep<2, ExpCoordinates>{problem, terms, {dexpinv}, aniso, K, L});
      case 3: return drive(MkStep<3, ExpCoordinates>{problem, terms, {dexpinv}, aniso, K, L});
      case 4: return drive(MkStep<4, ExpCoordinates>{problem, terms, {dexpinv}, aniso, K, L});
      default: return drive(MkStep<0, ExpCoordinates>{problem, terms, {dexpinv}, aniso, K, L});
    }
  });
}

std::unique_ptr<Integrator> rkmk_cayley_fixed(Tableau tableau, std::string name) {
  MethodInfo info{.name = std::move(name),
                  .family = "rkmk",
                  .declared_order = tableau.order(),
                  .description = "Runge-Kutta-Munthe-Kaas (" + tableau.name() +
                                 " tableau) with the Cayley map for coordinates; cayley maps counted as exp, "
                                 "dcayinv as dexpinv",
                  .on_group = true};
  return stepped_method(std::move(info), [tableau = std::move(tableau)](const Problem& problem, auto&& drive) {
    const StageTerms terms(tableau);
    std::array<Vec3, kMaxStages> K;
    std::array<ZState, kMaxStages> L;
    return drive(MkStep<0, CayleyCoordinates>{problem, terms, {}, problem.model().anisotropic(), K, L});
  });
}

}  // namespace rb

#include "integrators/families/rk/runge_kutta.hpp"

#include <array>

#include "integrators/stage_terms.hpp"
#include "integrators/steppers/stepped_method.hpp"

namespace rb {

namespace {

MethodInfo facts_of(const Tableau& tableau, std::string name) {
  return {.name = name.empty() ? tableau.name() : std::move(name),
          .family = "rk",
          .declared_order = tableau.order(),
          .description = "classical explicit RK (" + tableau.name() + " tableau, " + std::to_string(tableau.stages()) +
                         (tableau.stages() == 1 ? " stage" : " stages") + ") on the flat view",
          .tableau = tableau.name()};
}

// One step of an explicit tableau with S stages, S = 0 for any number. With S
// known the stage loop unrolls around the inlined right-hand side, and the
// compiler schedules each stage's sum into the tail of the evaluation before
// it (about a tenth of an RK4 step on valley-sideways).
template <int S>
struct RkStep {
  const Problem& problem;
  const StageTerms& terms;
  std::array<FlatState, kMaxStages>& k;
  FlatState& Y;

  // every stage's validity margins are noted in cost (stage_flat_rhs)
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) const {
    const int stages = S > 0 ? S : terms.stages;
    stage_flat_rhs(problem, y.data(), k[0].data(), cost);
    for (int i = 1; i < stages; ++i) {
      const StageTerms::Row& row = terms.a[static_cast<std::size_t>(i)];
      // the stage's state, y + h a_i0 k_0 + h a_i1 k_1 + ... (the non-zero
      // terms); with none y itself, uncopied
      const FlatState* at = &y;
      if (row.count > 0) {
        row.sum(Y, y, h, k);
        at = &Y;
      }
      stage_flat_rhs(problem, at->data(), k[static_cast<std::size_t>(i)].data(), cost);
    }
    terms.b.sum(next, y, h, k);
    cost.rhs_evals += stages;
  }
};

}  // namespace

std::unique_ptr<Integrator> rk_fixed(Tableau tableau, std::string name) {
  MethodInfo info = facts_of(tableau, std::move(name));
  return stepped_method(std::move(info), [tableau = std::move(tableau)](const Problem& problem, auto&& drive) {
    const StageTerms terms(tableau);
    std::array<FlatState, kMaxStages> k;
    FlatState Y;
    // the registry's tableaus have 1 to 4 stages, the larger ones go generic
    switch (terms.stages) {
      case 1: return drive(RkStep<1>{problem, terms, k, Y});
      case 2: return drive(RkStep<2>{problem, terms, k, Y});
      case 3: return drive(RkStep<3>{problem, terms, k, Y});
      case 4: return drive(RkStep<4>{problem, terms, k, Y});
      default: return drive(RkStep<0>{problem, terms, k, Y});
    }
  });
}

}  // namespace rb

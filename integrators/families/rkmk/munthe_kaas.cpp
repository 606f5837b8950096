#include "integrators/families/rkmk/munthe_kaas.hpp"

#include <algorithm>
#include <vector>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/rkmk/rkmk_stepper.hpp"
#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/stepped_method.hpp"
#include "integrators/steppers/tableau_methods.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

MethodInfo fixed_facts(const Tableau& tableau, std::string name, DexpinvKind dexpinv) {
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

std::string adaptive_description(const Tableau& p, const std::string& controller, bool use_dense) {
  const bool fsal_in_attempt = p.fsal_in_attempt();
  const int per_attempt = p.attempt_stages() - 1 + (fsal_in_attempt ? 0 : 1);
  // the stages past the attempt's, less the FSAL one (evaluated for the next step)
  const int extra = p.total_stages() - p.attempt_stages() - (p.fsal_stage() && !fsal_in_attempt ? 1 : 0);
  std::string text = "adaptive Runge-Kutta-Munthe-Kaas on the " + p.name() + " pair (order " +
                     std::to_string(p.order()) + ", error estimate on (u, z), " + controller_title(controller) +
                     " controller): " + std::to_string(per_attempt) + " rhs and " +
                     std::to_string(p.attempt_stages() - 1) + " dexpinv a step, one exp";
  if (use_dense)
    text += "; outputs by its order-" + std::to_string(p.dense_order()) + " dense output through exp" +
            (extra > 0 ? " (" + std::to_string(extra) + " extra rhs a step with outputs)" : std::string());
  else text += "; steps clamped onto the outputs";
  return text;
}

// What a pair's run adds to the stepper: its tolerances, its output times
// and whether they come from the dense output.
struct PairRun {
  const Tolerances& tol;
  const std::vector<double>& outputs;
  bool dense;
};

// The one maker: the RKMK stepper of one run, handed to use (stepped_method's
// drive, or adaptive_method's), which returns the run's result. Both choose
// the ball's code path (General); fixed steps (Estimating = false) unroll
// the stage loop for up to four stages, with the tableau's stage shape at
// compile time where it is a chain or dense (stage_terms.hpp), a pair
// chooses its dense output.
template <bool Estimating, class Coordinates, class Use>
RunResult with_rkmk_stepper(const Problem& problem, const Tableau& tableau, Coordinates map, const PairRun* pair,
                            Use&& use) {
  const StageTerms terms(tableau);
  RkmkStages stages;
  const bool general = problem.model().has_inertia();
  if constexpr (!Estimating) {
    auto fixed = [&]<int S>() {
      auto shaped = [&]<StageShape Shape>() {
        auto on_path = [&]<bool General>() {
          RkmkStepper<S, Coordinates, false, General, Shape> stepper(problem, tableau, terms, map, stages);
          return use(stepper);
        };
        return general ? on_path.template operator()<true>() : on_path.template operator()<false>();
      };
      if constexpr (S > 0) {
        const StageShape shape = terms.shape(S);
        if (shape == chain_shape(S)) return shaped.template operator()<chain_shape(S)>();
        if (shape == dense_shape(S)) return shaped.template operator()<dense_shape(S)>();
      }
      return shaped.template operator()<kRuntimeShape>();
    };
    switch (terms.stages) {
      case 1: return fixed.template operator()<1>();
      case 2: return fixed.template operator()<2>();
      case 3: return fixed.template operator()<3>();
      case 4: return fixed.template operator()<4>();
      default: return fixed.template operator()<0>();
    }
  } else {
    auto run = [&]<bool Dense, bool General>() {
      RkmkStepper<0, Coordinates, Dense, General> stepper(problem, tableau, terms, map, stages, pair->tol,
                                                          pair->outputs);
      return use(stepper);
    };
    if (pair->dense) return general ? run.template operator()<true, true>() : run.template operator()<true, false>();
    return general ? run.template operator()<false, true>() : run.template operator()<false, false>();
  }
}

}  // namespace

std::unique_ptr<Integrator> rkmk_integrator(Tableau tableau, std::string name, const std::string& controller,
                                            DexpinvKind dexpinv, bool use_dense) {
  if (controller == kConstantController) {
    MethodInfo info = fixed_facts(tableau, std::move(name), dexpinv);
    return stepped_method(
        std::move(info), [tableau = std::move(tableau), dexpinv](const Problem& problem, auto&& drive) {
          if (dexpinv == DexpinvKind::exact)
            return with_rkmk_stepper<false>(problem, tableau, ClosedFormExpCoordinates{}, nullptr, drive);
          return with_rkmk_stepper<false>(problem, tableau, ExpCoordinates{dexpinv}, nullptr, drive);
        });
  }
  if (dexpinv != DexpinvKind::exact)
    throw InputError("'" + name + "': only the closed-form dexpinv has an adaptive RKMK", "controller");
  require_embedded_pair(tableau, controller);
  use_dense = use_dense && tableau.dense_order() > 0;
  MethodInfo info{.name = std::move(name),
                  .family = "rkmk-adaptive",
                  .declared_order = tableau.order(),
                  .embedded_order = tableau.embedded_order(),
                  .controller = controller,
                  .description = adaptive_description(tableau, controller, use_dense),
                  .tableau = tableau.name(),
                  .on_group = true};
  return adaptive_method(std::move(info),
                         [tableau = std::move(tableau), use_dense](const Problem& problem, const RunOptions& options,
                                                                   const Tolerances& tol, auto&& drive) {
                           const std::vector<double> outputs = output_times_of(problem, options);
                           const PairRun pair{tol, outputs, use_dense};
                           return with_rkmk_stepper<true>(problem, tableau, ClosedFormExpCoordinates{}, &pair, drive);
                         });
}

std::unique_ptr<Integrator> rkmk_cayley_integrator(Tableau tableau, std::string name, const std::string& controller) {
  if (controller != kConstantController)
    throw InputError("'" + name + "': RKMK with the Cayley map runs at fixed steps only", "controller");
  MethodInfo info{.name = std::move(name),
                  .family = "rkmk",
                  .declared_order = tableau.order(),
                  .description = "Runge-Kutta-Munthe-Kaas (" + tableau.name() +
                                 " tableau) with the Cayley map for coordinates; cayley maps counted as exp, "
                                 "dcayinv as dexpinv",
                  .on_group = true};
  return stepped_method(std::move(info), [tableau = std::move(tableau)](const Problem& problem, auto&& drive) {
    return with_rkmk_stepper<false>(problem, tableau, CayleyCoordinates{}, nullptr, drive);
  });
}

}  // namespace rb

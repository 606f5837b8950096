#include "integrators/families/exp_product/exp_product.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/exp_product/exp_product_stepper.hpp"
#include "integrators/steppers/adaptive_method.hpp"
#include "integrators/steppers/stepped_method.hpp"

namespace rb {

namespace {

using Row = ExpRow;

Row row_of(const FieldSum& sum, std::size_t fields, const std::string& where) {
  if (sum.size() > fields) throw std::invalid_argument(where + " uses a field not yet computed");
  Row row;
  for (std::size_t j = 0; j < sum.size(); ++j) row.add(static_cast<int>(j), sum[j]);
  return row;
}

// the non-zero factors of a product
std::vector<FieldSum> nonzero_factors(const ExpProduct& product) {
  std::vector<FieldSum> out;
  for (const FieldSum& f : product)
    if (std::any_of(f.begin(), f.end(), [](double c) { return c != 0.0; })) out.push_back(f);
  return out;
}

// a Row summing the coefficients of every factor (the z part of the product)
Row z_row_of(const std::vector<FieldSum>& factors, std::size_t fields) {
  FieldSum total(fields, 0.0);
  for (const FieldSum& f : factors)
    for (std::size_t j = 0; j < f.size(); ++j) total[j] += f[j];
  return row_of(total, fields, "");
}

}  // namespace

ExpPlan plan_of(const ExpProductScheme& scheme) {
  const std::size_t s = scheme.stages.size();
  if (s < 1 || s > static_cast<std::size_t>(kMaxStages) || !scheme.stages[0].empty())
    throw std::invalid_argument(scheme.name + ": 1 to 16 stages, the first with no exponentials");
  ExpPlan plan;
  plan.stages = static_cast<int>(s);
  std::vector<std::vector<FieldSum>> factors(s);
  auto plan_product = [&](const std::vector<FieldSum>& mine, std::size_t fields, const std::string& where,
                          std::size_t earlier_stages) {
    PlannedProduct p;
    std::size_t skip = 0;
    // the longest earlier stage product that starts this one
    for (std::size_t k = 1; k < earlier_stages; ++k)
      if (!factors[k].empty() && factors[k].size() > skip && factors[k].size() <= mine.size() &&
          std::equal(factors[k].begin(), factors[k].end(), mine.begin())) {
        p.base = static_cast<int>(k);
        skip = factors[k].size();
      }
    for (std::size_t n = skip; n < mine.size(); ++n)
      p.factor[static_cast<std::size_t>(p.count++)] = row_of(mine[n], fields, where);
    return p;
  };
  for (std::size_t i = 1; i < s; ++i) {
    const std::string where = scheme.name + " stage " + std::to_string(i + 1);
    factors[i] = nonzero_factors(scheme.stages[i]);
    if (factors[i].size() > static_cast<std::size_t>(kMaxStages))
      throw std::invalid_argument(where + ": too many factors");
    plan.stage[i] = plan_product(factors[i], i, where, i);
    plan.z_stage[i] = z_row_of(factors[i], i);
  }
  const std::vector<FieldSum> update = nonzero_factors(scheme.update);
  if (update.empty() || update.size() > static_cast<std::size_t>(kMaxStages))
    throw std::invalid_argument(scheme.name + ": the update needs 1 to 16 exponentials");
  plan.update = plan_product(update, s, scheme.name + " update", 1);
  plan.z_update = z_row_of(update, s);
  const std::vector<FieldSum> embedded = nonzero_factors(scheme.embedded);
  if (embedded.size() > static_cast<std::size_t>(kMaxStages))
    throw std::invalid_argument(scheme.name + ": the embedded update needs at most 16 exponentials");
  plan.embedded = plan_product(embedded, s, scheme.name + " embedded update", 1);
  plan.z_embedded = z_row_of(embedded, s);
  if (scheme.embedded_order > 0) plan.error_order = std::min(scheme.order, scheme.embedded_order) + 1;
  // the stages the update reads, and those they read (each only earlier ones)
  plan.propagating = 1;
  auto reads = [&plan](const ExpRow& row) {
    if (row.count > 0)
      plan.propagating = std::max(plan.propagating, row.index[static_cast<std::size_t>(row.count - 1)] + 1);
  };
  for (std::size_t n = 0; n < static_cast<std::size_t>(plan.update.count); ++n) reads(plan.update.factor[n]);
  reads(plan.z_update);
  return plan;
}

namespace {

// the exponentials of a fixed step over the stages the update reads
int exponentials_of(const ExpPlan& plan, bool anisotropic) {
  int n = plan.update.count;
  if (anisotropic)
    for (std::size_t i = 1; i < static_cast<std::size_t>(plan.propagating); ++i) n += plan.stage[i].count;
  return n;
}

MethodInfo fixed_facts(const ExpProductScheme& scheme, const ExpPlan& plan) {
  return {.name = scheme.name,
          .family = scheme.family,
          .declared_order = scheme.order,
          .rotation_order = scheme.rotation_order,
          .description = std::to_string(plan.propagating) + "-stage " + scheme.kind +
                         " method on the Lie-group view, " + std::to_string(exponentials_of(plan, true)) +
                         " exponentials a step (" + std::to_string(exponentials_of(plan, false)) +
                         " for a homogeneous ball): " + scheme.source,
          .on_group = true};
}

// Throws std::invalid_argument for a scheme without an embedded update.
MethodInfo adaptive_facts(const ExpProductScheme& scheme, const ExpPlan& plan, const std::string& controller) {
  if (scheme.embedded_order < 1 || plan.embedded.count == 0)
    throw std::invalid_argument(scheme.name + ": an adaptive method needs an embedded update and its order");
  int stage_exps = 0;
  for (std::size_t i = 1; i < static_cast<std::size_t>(plan.stages); ++i) stage_exps += plan.stage[i].count;
  const int update_exps = plan.update.count + plan.embedded.count;
  return {.name = scheme.name,
          .family = scheme.family + "-adaptive",
          .declared_order = scheme.order,
          .embedded_order = scheme.embedded_order,
          .controller = controller,
          .description = "adaptive " + scheme.kind + " method, order " + std::to_string(scheme.order) +
                         " with an embedded order-" + std::to_string(scheme.embedded_order) +
                         " update (error on (rotation vector, z), " + controller_title(controller) + " controller): " +
                         std::to_string(plan.stages - 1) + " rhs and " + std::to_string(stage_exps + update_exps) +
                         " exponentials an attempt (" + std::to_string(update_exps) +
                         " for a homogeneous ball); steps clamped onto the outputs: " + scheme.source,
          .on_group = true};
}

}  // namespace

int exponentials_per_step(const ExpProductScheme& scheme, bool anisotropic) {
  return exponentials_of(plan_of(scheme), anisotropic);
}

std::unique_ptr<Integrator> exp_product_method(ExpProductScheme scheme, std::string name,
                                               const std::string& controller) {
  scheme.name = std::move(name);
  const bool fixed = controller == kConstantController;
  if (!fixed) (void)filter_controller(controller);  // throws for an unknown one
  // (plan_of rejects a malformed scheme here, not in a run)
  ExpPlan plan = plan_of(scheme);
  MethodInfo info = fixed ? fixed_facts(scheme, plan) : adaptive_facts(scheme, plan, controller);
  // the one stepper of both ways of stepping, made for a run (its stage
  // storage in this frame); tol: none at fixed steps
  auto with_stepper = [plan = std::move(plan)](const Problem& problem, const Tolerances& tol, auto&& drive) {
    ExpProductStepper stepper(problem, plan, tol);
    return drive(stepper);
  };
  if (fixed)
    return stepped_method(std::move(info), [with = std::move(with_stepper)](const Problem& problem, auto&& drive) {
      return with(problem, Tolerances(), drive);
    });
  return adaptive_method(std::move(info), [with = std::move(with_stepper)](const Problem& problem, const RunOptions&,
                                                                           const Tolerances& tol, auto&& drive) {
    return with(problem, tol, drive);
  });
}

}  // namespace rb

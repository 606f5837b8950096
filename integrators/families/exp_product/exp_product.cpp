#include "integrators/families/exp_product/exp_product.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "integrators/controllers/controller.hpp"
#include "integrators/families/exp_product/exp_product_adaptive.hpp"
#include "integrators/families/exp_product/exp_product_stages.hpp"
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
  return plan;
}

int exponentials_per_step(const ExpProductScheme& scheme, bool anisotropic) {
  const ExpPlan plan = plan_of(scheme);
  int n = plan.update.count;
  if (anisotropic)
    for (std::size_t i = 1; i < static_cast<std::size_t>(plan.stages); ++i) n += plan.stage[i].count;
  return n;
}

namespace {

// (plan_of, through the counts, rejects a malformed scheme here, not in a run)
MethodInfo facts_of(const ExpProductScheme& scheme) {
  return {.name = scheme.name,
          .family = scheme.family,
          .declared_order = scheme.order,
          .rotation_order = scheme.rotation_order,
          .description = std::to_string(scheme.stages.size()) + "-stage " + scheme.kind +
                         " method on the Lie-group view, " + std::to_string(exponentials_per_step(scheme, true)) +
                         " exponentials a step (" + std::to_string(exponentials_per_step(scheme, false)) +
                         " for a homogeneous ball): " + scheme.source,
          .on_group = true};
}

}  // namespace

std::unique_ptr<Integrator> exp_product_method(ExpProductScheme scheme, std::string name,
                                               const std::string& controller) {
  scheme.name = std::move(name);
  if (controller != kConstantController) return exp_product_adaptive(std::move(scheme), controller);
  MethodInfo info = facts_of(scheme);
  return stepped_method(std::move(info), [plan = plan_of(scheme)](const Problem& problem, auto&& drive) {
    std::array<Vec3, kMaxStages> K;
    std::array<ZState, kMaxStages> L;
    std::array<Mat3, kMaxStages> Rs;
    return drive(ExpProductStep{problem, plan, problem.model().anisotropic(), K, L, Rs});
  });
}

}  // namespace rb

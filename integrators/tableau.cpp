#include "integrators/tableau.hpp"

#include <cmath>

#include "integrators/order_conditions.hpp"
#include "problems/input_error.hpp"

namespace rb {

Tableau::Tableau(std::string name, int order, std::vector<double> a, std::vector<double> b,
                 std::vector<double> c)
    : name_(std::move(name)), order_(order), a_(std::move(a)), b_(std::move(b)), c_(std::move(c)) {
  const std::size_t s = b_.size();
  if (s == 0 || s > static_cast<std::size_t>(kMaxStages))
    throw InputError("a tableau needs 1 to " + std::to_string(kMaxStages) + " stages, got " + std::to_string(s), "b");
  if (a_.size() != s * s) throw InputError("A must be " + std::to_string(s) + " x " + std::to_string(s), "a");
  if (c_.size() != s) throw InputError("c must have " + std::to_string(s) + " entries", "c");
  if (order_ < 1) throw InputError("the declared order must be >= 1", "order");
  for (double x : a_)
    if (!std::isfinite(x)) throw InputError("A has a non-finite entry", "a");
  for (std::size_t i = 0; i < s; ++i) {
    if (!std::isfinite(b_[i]) || !std::isfinite(c_[i])) throw InputError("b and c must be finite", "b");
    double row = 0.0;
    for (std::size_t j = 0; j < s; ++j) {
      if (j >= i && a_[i * s + j] != 0.0)
        throw InputError("A must be strictly lower triangular for an explicit method (a[" + std::to_string(i) +
                             "][" + std::to_string(j) + "] != 0)",
                         "a");
      row += a_[i * s + j];
    }
    if (std::abs(row - c_[i]) > 1e-12)
      throw InputError("c[" + std::to_string(i) + "] must equal the sum of row " + std::to_string(i) + " of A", "c");
  }
  // every rooted tree up to the declared order (integrators/order_conditions.hpp)
  if (order_ > kMaxConditionOrder)
    throw InputError("order conditions are checked up to order " + std::to_string(kMaxConditionOrder) +
                         ", the declared order is " + std::to_string(order_),
                     "order");
  const OrderConditionCheck check = check_order_conditions(stages(), a_, b_, c_, order_);
  if (check.failure)
    throw InputError("tableau '" + name_ + "' declares order " + std::to_string(order_) +
                         " but satisfies the order conditions only to order " + std::to_string(check.satisfied_order) +
                         " (" + describe(*check.failure) + ")",
                     "order");
}

int Tableau::satisfied_order() const {
  return check_order_conditions(stages(), a_, b_, c_, kMaxConditionOrder).satisfied_order;
}

}  // namespace rb

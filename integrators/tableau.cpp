#include "integrators/tableau.hpp"

#include <algorithm>
#include <cmath>

#include "integrators/order_conditions.hpp"
#include "problems/input_error.hpp"

namespace rb {

namespace {

// One past the last non-zero entry of w.
int support_of(const std::vector<double>& w) {
  int n = static_cast<int>(w.size());
  while (n > 0 && w[static_cast<std::size_t>(n - 1)] == 0.0) --n;
  return n;
}

void check_finite(const std::vector<double>& v, const char* what, const char* key) {
  for (double x : v)
    if (!std::isfinite(x)) throw InputError(std::string(what) + " has a non-finite entry", key);
}

// The order conditions of weights w (b, or an embedded member) up to
// order; subject names them in the message ("tableau 'x'" declares, "the
// embedded weights ..." declare).
void check_conditions(const TableauCoefficients& k, const std::vector<double>& w, int order, const std::string& subject,
                      bool plural, const char* key) {
  if (order < 1) throw InputError(subject + ": the declared order must be >= 1", key);
  if (order > kMaxConditionOrder)
    throw InputError("order conditions are checked up to order " + std::to_string(kMaxConditionOrder) +
                         ", the declared order is " + std::to_string(order),
                     key);
  const OrderConditionCheck check =
      check_order_conditions(static_cast<int>(w.size()), k.a, w, k.c, order, 1.0, k.order_tolerance);
  if (check.failure)
    throw InputError(subject + (plural ? " declare order " : " declares order ") + std::to_string(order) +
                         (plural ? " but satisfy" : " but satisfies") + " the order conditions only to order " +
                         std::to_string(check.satisfied_order) + " (" + describe(*check.failure) + ")",
                     key);
}

// An embedded member's weights b - e, checked to its order (e may be
// b_hat - b as well: b - e = 2 b - b_hat then holds exactly the conditions
// b_hat holds, when b's order is the higher).
void check_embedded(const TableauCoefficients& k, const std::vector<double>& e, int order, const char* key) {
  if (e.empty()) return;
  if (e.size() != k.b.size())
    throw InputError(std::string(key) + " must have " + std::to_string(k.b.size()) + " entries", key);
  check_finite(e, key, key);
  if (support_of(e) == 0) throw InputError(std::string(key) + " is zero: the error estimate would vanish", key);
  std::vector<double> b_hat(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) b_hat[i] = k.b[i] - e[i];
  check_conditions(k, b_hat, order, "the embedded weights b - " + std::string(key) + " of tableau '" + k.name + "'",
                   true, key);
}

TableauCoefficients plain(std::string name, int order, std::vector<double> a, std::vector<double> b,
                          std::vector<double> c, std::string source) {
  TableauCoefficients k;
  k.name = std::move(name);
  k.order = order;
  k.a = std::move(a);
  k.b = std::move(b);
  k.c = std::move(c);
  k.source = std::move(source);
  return k;
}

}  // namespace

Tableau::Tableau(std::string name, int order, std::vector<double> a, std::vector<double> b, std::vector<double> c,
                 std::string source)
    : Tableau(plain(std::move(name), order, std::move(a), std::move(b), std::move(c), std::move(source))) {}

Tableau::Tableau(TableauCoefficients coefficients) : k_(std::move(coefficients)) {
  const std::size_t s = k_.b.size();
  if (s == 0 || s > static_cast<std::size_t>(kMaxStages))
    throw InputError("a tableau needs 1 to " + std::to_string(kMaxStages) + " stages, got " + std::to_string(s), "a");
  if (k_.a.size() != s * s) throw InputError("A must be " + std::to_string(s) + " x " + std::to_string(s), "a");
  if (k_.c.size() != s) throw InputError("c must have " + std::to_string(s) + " entries", "c");
  if (k_.order < 1) throw InputError("the declared order must be >= 1", "order");
  if (!(k_.order_tolerance > 0.0 && k_.order_tolerance <= kMaxOrderTolerance))
    throw InputError("must be " + order_tolerance_rule(), "order_tolerance");
  check_finite(k_.a, "A", "a");
  for (std::size_t i = 0; i < s; ++i) {
    if (!std::isfinite(k_.b[i]) || !std::isfinite(k_.c[i])) throw InputError("b and c must be finite", "b");
    double row = 0.0;
    for (std::size_t j = 0; j < s; ++j) {
      if (j >= i && k_.a[i * s + j] != 0.0)
        throw InputError("A must be strictly lower triangular for an explicit method (a[" + std::to_string(i) + "][" +
                             std::to_string(j) + "] != 0)",
                         "a");
      row += k_.a[i * s + j];
    }
    if (!(std::abs(row - k_.c[i]) <= k_.order_tolerance))
      throw InputError("c[" + std::to_string(i) + "] must equal the sum of row " + std::to_string(i) + " of A", "c");
  }
  // every rooted tree up to each declared order (integrators/order_conditions.hpp)
  check_conditions(k_, k_.b, k_.order, "tableau '" + k_.name + "'", false, "order");
  check_embedded(k_, k_.e, k_.embedded_order, "e");
  if (!k_.e_stretched.empty() && k_.e.empty())
    throw InputError("a stretched estimate goes with the embedded weights e", "e_stretched");
  check_embedded(k_, k_.e_stretched, k_.stretched_order, "e_stretched");
  if (k_.dense_order > 0) {
    if (k_.dense_degree < 1 || k_.dense.size() != s * static_cast<std::size_t>(k_.dense_degree))
      throw InputError("the dense weights must be " + std::to_string(s) + " x dense_degree", "dense");
    check_finite(k_.dense, "dense", "dense");
    // b_i(1) = sum_k dense_ik must be b_i: the continuous extension ends where the step does
    for (std::size_t i = 0; i < s; ++i) {
      double at_one = 0.0;
      for (int q = 0; q < k_.dense_degree; ++q) at_one += k_.dense[i * static_cast<std::size_t>(k_.dense_degree) + q];
      if (!(std::abs(at_one - k_.b[i]) <= k_.order_tolerance))
        throw InputError("the dense weights at theta = 1 must equal b (stage " + std::to_string(i) + ")", "dense");
    }
  } else if (!k_.dense.empty()) {
    throw InputError("dense weights need their dense_order", "dense");
  }

  // the stage groups and the FSAL stage, from the coefficients alone
  stages_ = support_of(k_.b);
  attempt_stages_ = std::max({stages_, support_of(k_.e), support_of(k_.e_stretched)});
  for (std::size_t i = static_cast<std::size_t>(stages_); i < s && !fsal_; ++i) {
    bool row_is_b = i > 0 && k_.c[i] == 1.0;
    for (std::size_t j = 0; j < i && row_is_b; ++j) row_is_b = k_.a[i * s + j] == k_.b[j];
    if (row_is_b) fsal_ = static_cast<int>(i);
  }
}

int Tableau::error_order() const {
  if (k_.e.empty()) return 0;
  const int k = std::min(k_.order, k_.embedded_order) + 1;
  if (k_.e_stretched.empty()) return k;
  return 2 * k - (std::min(k_.order, k_.stretched_order) + 1);
}

int Tableau::satisfied_order() const {
  return check_order_conditions(total_stages(), k_.a, k_.b, k_.c, kMaxConditionOrder, 1.0, k_.order_tolerance)
      .satisfied_order;
}

}  // namespace rb

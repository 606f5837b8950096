#include "integrators/tableau.hpp"

#include <cmath>

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
  const int p = satisfied_order();
  if (p < std::min(order_, 4))
    throw InputError("tableau '" + name_ + "' declares order " + std::to_string(order_) +
                         " but satisfies the order conditions only to order " + std::to_string(p),
                     "order");
}

int Tableau::satisfied_order() const {
  const int s = stages();
  auto sum = [&](auto&& term) {
    double total = 0.0;
    for (int i = 0; i < s; ++i) total += term(i);
    return total;
  };
  // (A c)_i and (A c^2)_i and (A A c)_i
  std::vector<double> ac(s, 0.0), ac2(s, 0.0), aac(s, 0.0);
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < s; ++j) {
      ac[i] += a(i, j) * c(j);
      ac2[i] += a(i, j) * c(j) * c(j);
    }
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < s; ++j) aac[i] += a(i, j) * ac[j];
  auto holds = [](double value, double expected) { return std::abs(value - expected) <= 1e-12; };
  if (!holds(sum([&](int i) { return b(i); }), 1.0)) return 0;
  if (!holds(sum([&](int i) { return b(i) * c(i); }), 0.5)) return 1;
  if (!holds(sum([&](int i) { return b(i) * c(i) * c(i); }), 1.0 / 3.0) ||
      !holds(sum([&](int i) { return b(i) * ac[i]; }), 1.0 / 6.0))
    return 2;
  if (!holds(sum([&](int i) { return b(i) * c(i) * c(i) * c(i); }), 0.25) ||
      !holds(sum([&](int i) { return b(i) * c(i) * ac[i]; }), 0.125) ||
      !holds(sum([&](int i) { return b(i) * ac2[i]; }), 1.0 / 12.0) ||
      !holds(sum([&](int i) { return b(i) * aac[i]; }), 1.0 / 24.0))
    return 3;
  return 4;
}

}  // namespace rb

#pragma once
// An explicit Butcher tableau that checks itself: strictly lower-triangular
// A, c_i = sum_j a_ij, and the order conditions of every rooted tree up to
// its declared order (integrators/order_conditions.hpp).
#include <string>
#include <vector>

namespace rb {

class Tableau {
 public:
  // a: s x s row-major (only the strictly lower triangle may be non-zero),
  // b: s weights, c: s nodes. Throws InputError naming what fails.
  Tableau(std::string name, int order, std::vector<double> a, std::vector<double> b, std::vector<double> c);

  const std::string& name() const { return name_; }
  int order() const { return order_; }
  int stages() const { return static_cast<int>(b_.size()); }
  double a(int i, int j) const { return a_[static_cast<std::size_t>(i * stages() + j)]; }
  double b(int i) const { return b_[static_cast<std::size_t>(i)]; }
  double c(int i) const { return c_[static_cast<std::size_t>(i)]; }

  // The largest p <= 10 (kMaxConditionOrder) whose order conditions hold to 1e-12.
  int satisfied_order() const;

 private:
  std::string name_;
  int order_;
  std::vector<double> a_, b_, c_;
};

// The most stages any tableau may have; step loops keep this many stage
// vectors on the stack.
inline constexpr int kMaxStages = 16;

}  // namespace rb

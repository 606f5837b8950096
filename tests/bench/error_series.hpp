#pragma once
// A synthetic error series for the order-fit tests: e(h) for each step h.
#include <vector>

namespace rb {

template <class F>
std::vector<double> errors(const std::vector<double>& h, F&& f) {
  std::vector<double> e;
  for (double x : h) e.push_back(f(x));
  return e;
}

}  // namespace rb

#pragma once
// A synthetic error series for the order-fit tests: e(h) for each step h,
// over the default preset's ladder of steps.
#include <cmath>
#include <vector>

namespace rb {

template <class F>
std::vector<double> errors(const std::vector<double>& h, F&& f) {
  std::vector<double> e;
  for (double x : h) e.push_back(f(x));
  return e;
}

// the default preset's ladder shape: quarter steps 2^0 .. 2^-8, then 2^-9 .. 2^-to
inline std::vector<double> ladder(int to) {
  std::vector<double> h;
  for (int k = 0; k <= 32; ++k) h.push_back(std::exp2(-k / 4.0));
  for (int k = 9; k <= to; ++k) h.push_back(std::ldexp(1.0, -k));
  return h;
}

}  // namespace rb

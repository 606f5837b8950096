#pragma once
// A sparse way to write a tableau's matrix in a method file: the non-zero
// entries only (the high-order tableaus are half zeros).
#include <initializer_list>
#include <vector>

namespace rb::methods {

struct Entry {
  int i, j;
  double value;
};

// The n x n row-major matrix with these entries, zero elsewhere.
inline std::vector<double> matrix(int n, std::initializer_list<Entry> entries) {
  std::vector<double> m(static_cast<std::size_t>(n * n), 0.0);
  for (const Entry& x : entries) m[static_cast<std::size_t>(x.i * n + x.j)] = x.value;
  return m;
}

}  // namespace rb::methods

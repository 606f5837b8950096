#pragma once
// A composition method: one step of h is the substeps gamma_1 h, ...,
// gamma_m h of a base stepper in turn (integrators/families/symmetric/gauss_tableaux.hpp's
// triple_jump gives symmetric gammas that raise a symmetric order-2 method
// to order 4 or 6). Each substep's stages are noted and counted by the base
// stepper, so the cost and the validity checks are the base's summed.
#include <cstddef>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

template <class Step>
struct Composed {
  Step step;                          // a stepper of the shape (y, next, t, h, cost)
  const std::vector<double>* gammas;  // the substeps' fractions of h, summing to 1
  FlatState between[2];               // the states between substeps, used in turn

  void operator()(const FlatState& y, FlatState& next, double t, double h, Cost& cost) {
    const std::size_t m = gammas->size();
    const FlatState* from = &y;
    for (std::size_t k = 0; k < m; ++k) {
      const double hk = (*gammas)[k] * h;
      FlatState& to = k + 1 == m ? next : between[k % 2];
      step(*from, to, t, hk, cost);
      t += hk;
      from = &to;
    }
  }
};

}  // namespace rb

#pragma once
// The try/accept skeleton every embedded pair the suite's controllers drive
// shares (the flat, Lie and exponential-product pairs): the error-estimating
// stepper protocol of integrators/adaptive_loops.hpp written once, the pair itself
// (CRTP) saying only how its stages and its state work:
//
//   void first_stage(Cost&);           the stage at the current state
//   double attempt(double h, Cost&);   the other stages and the error norm
//                                      of a step of h, kept for commit
//   bool tried_finite() const;         that step's state is finite
//   bool commit(double t, double h, Cost&);
//       makes the tried step the current state; true when the next step's
//       first stage is already known (FSAL, or evaluated here)
//   void go_back(const FlatState& y);  the state back to y
//
// The first stage is evaluated by the attempt that needs it (so that its
// validity margins are that attempt's), unless commit has it.
#include <cmath>
#include <limits>

#include "integrators/driver.hpp"

namespace rb {

template <class Pair>
class EmbeddedPair {
 public:
  // The error norm of a step of h from the current state (NaN when the step
  // is not finite); the state is unchanged.
  double try_step(double /*t*/, double h, Cost& cost) {
    if (!have_first_) {
      pair().first_stage(cost);
      have_first_ = true;
    }
    const double err = pair().attempt(h, cost);
    return pair().tried_finite() ? err : std::numeric_limits<double>::quiet_NaN();
  }

  void accept(double t, double h, Cost& cost) { have_first_ = pair().commit(t, h, cost); }

  // back to y, the state before a step the driver refused after accepting
  // it; the first stage there is evaluated again by the next attempt
  void restore(const FlatState& y) {
    pair().go_back(y);
    have_first_ = false;
  }

 private:
  Pair& pair() { return static_cast<Pair&>(*this); }
  bool have_first_ = false;
};

}  // namespace rb

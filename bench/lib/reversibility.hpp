#pragma once
// The reversibility defect of a method (docs/model.md, "Time reversal"): the
// equations are reversible under rho(R, v, alpha) = (R, -v, alpha), so the
// exact flow phi_t satisfies rho phi_t rho phi_t = id. A method's defect is
// how far N steps forward, rho, N steps forward and rho again land from the
// start: at rounding for a symmetric method, O(h^p) for an explicit one.
#include <string>

#include "integrators/integrator.hpp"
#include "problems/problem.hpp"

namespace rb {

// rho: R and the contact point kept, the angular momentum v = T omega negated.
FlatState time_reversed(const FlatState& y);

struct ReversibilityDefect {
  Status status = Status::ok;  // of the first failing leg; ok when both reached t_end
  std::string message;
  long steps = 0;         // per leg
  double contact = 0.0;   // |alpha_back - alpha_0| / r
  double rotation = 0.0;  // the angle of R_back R_0^T (rad)
  double momentum = 0.0;  // |v_back - v_0| / |v_0| (absolute where v_0 = 0)
  double worst() const;   // the largest of the three
};

// Runs method over [0, t_end] with options (h for a fixed-step method, the
// tolerances for an adaptive one) from the problem's start, reverses,
// runs again from there, reverses, and measures the distance to the start.
ReversibilityDefect reversibility_defect(const Integrator& method, const Problem& problem, RunOptions options);

// The same from a forward run already made with options (the sweep's timed
// run): only the leg back is run. forward must have status ok.
ReversibilityDefect reversibility_after(const Integrator& method, const Problem& problem, RunOptions options,
                                        const RunResult& forward);

}  // namespace rb

#include "bench/lib/reversibility.hpp"

#include <algorithm>

#include "problems/so3.hpp"

namespace rb {

FlatState time_reversed(const FlatState& y) {
  FlatState out = y;
  out.segment<3>(kOffsetV) = -y.segment<3>(kOffsetV);
  return out;
}

double ReversibilityDefect::worst() const { return std::max({contact, rotation, momentum}); }

ReversibilityDefect reversibility_defect(const Integrator& method, const Problem& problem, RunOptions options) {
  ReversibilityDefect d;
  options.output_times.clear();
  const RunResult forward = method.integrate(problem, options);
  if (forward.status != Status::ok) {
    d.steps = forward.cost.steps;
    d.status = forward.status;
    d.message = "forward: " + forward.message;
    return d;
  }
  return reversibility_after(method, problem, options, forward);
}

ReversibilityDefect reversibility_after(const Integrator& method, const Problem& problem, RunOptions options,
                                        const RunResult& forward) {
  ReversibilityDefect d;
  options.output_times.clear();
  d.steps = forward.cost.steps;
  // the same scene started from the reversed end state
  const Problem back_problem(problem.name(), problem.model(), time_reversed(forward.final_state), problem.t_end(),
                             problem.domain());
  const RunResult back = method.integrate(back_problem, options);
  if (back.status != Status::ok) {
    d.status = back.status;
    d.message = "back: " + back.message;
    return d;
  }
  const FlatState y0 = problem.y0(), y1 = time_reversed(back.final_state);
  const double radius = problem.model().params().radius;
  const double v0 = momentum_of(y0).norm();
  d.contact = (contact_of(y1) - contact_of(y0)).norm() / radius;
  d.rotation = rotation_angle_between(rotation_of(y1), rotation_of(y0));
  d.momentum = (momentum_of(y1) - momentum_of(y0)).norm() / (v0 > 0.0 ? v0 : 1.0);
  return d;
}

}  // namespace rb

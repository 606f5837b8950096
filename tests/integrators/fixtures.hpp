#pragma once
// The scene and run options most integrator tests share.
#include "integrators/integrator.hpp"
#include "problems/problem.hpp"
#include "problems/scene.hpp"

namespace rb::testing {

// valley-sideways: the seminar's landscape with a sideways start, every
// term of the equations of motion at work
inline const Problem& valley() {
  static const Problem problem = make_problem(load_scene("valley-sideways"));
  return problem;
}

// a fixed step h to t_end, output at t_end only
inline RunOptions fixed(double h, double t_end) {
  RunOptions o;
  o.h = h;
  o.t_end = t_end;
  return o;
}

// a fixed step h to t_end, with an output every dt
inline RunOptions every(double dt, double t_end, double h) {
  RunOptions o;
  o.t_end = t_end;
  o.h = h;
  for (int k = 1; k * dt < t_end - 1e-12; ++k) o.output_times.push_back(k * dt);
  return o;
}

}  // namespace rb::testing

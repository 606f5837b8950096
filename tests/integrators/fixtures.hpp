#pragma once
// The scene and run options most integrator tests share.
#include <map>
#include <string>

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

// a shipped scene by name, loaded once
inline const Problem& shipped_scene(const std::string& name) {
  static std::map<std::string, Problem> problems;
  auto it = problems.find(name);
  if (it == problems.end()) it = problems.emplace(name, make_problem(load_scene(name))).first;
  return it->second;
}

// an adaptive run at rtol = atol = tol to t_end, with an output every dt
inline RunOptions tolerance_every(double tol, double dt, double t_end) {
  RunOptions o;
  o.t_end = t_end;
  o.tolerances = Tolerances(tol, tol);
  for (int k = 1; k * dt < t_end - 1e-12; ++k) o.output_times.push_back(k * dt);
  return o;
}

}  // namespace rb::testing

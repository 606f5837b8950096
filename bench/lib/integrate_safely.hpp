#pragma once
// One run of a method in a study (sweep, stability, horizon): an exception
// the method throws for an option it cannot take is a failed run with its
// message, never a failed study (docs/bad-input.md).
#include <exception>

#include "integrators/integrator.hpp"
#include "problems/utf8.hpp"

namespace rb {

inline RunResult integrate_safely(const Integrator& m, const Problem& problem, const RunOptions& o) {
  try {
    return m.integrate(problem, o);
  } catch (const std::exception& e) {
    RunResult run;
    run.status = Status::error;
    run.message = valid_utf8(e.what());  // an exception's text may quote a path: any bytes
    run.final_state = problem.y0();
    return run;
  }
}

}  // namespace rb

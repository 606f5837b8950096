#include "problems/status.hpp"

namespace rb {

std::string_view status_name(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::diverged: return "diverged";
    case Status::lift_off: return "lift-off";
    case Status::curvature: return "curvature";
    case Status::domain: return "domain";
    case Status::step_underflow: return "step-underflow";
    case Status::max_steps: return "max-steps";
    case Status::crashed: return "crashed";
    case Status::timeout: return "timeout";
    case Status::off_group: return "off-group";
    case Status::chart_limit: return "chart-limit";
    case Status::solver: return "solver";
    case Status::error: return "error";
  }
  return "error";
}

}  // namespace rb

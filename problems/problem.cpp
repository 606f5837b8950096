#include "problems/problem.hpp"

#include <cmath>
#include <sstream>

namespace rb {

namespace {

std::string describe(const char* what, double value) {
  std::ostringstream s;
  s.precision(6);
  s << what << value;
  return s.str();
}

}  // namespace

Validity Problem::check_step(const FlatState& y) const {
  if (!y.allFinite()) return {Status::diverged, "the state is not finite"};
  if (!domain_.contains(y[kOffsetAlpha], y[kOffsetAlpha + 1])) {
    std::ostringstream s;
    s.precision(6);
    s << "the contact point (" << y[kOffsetAlpha] << ", " << y[kOffsetAlpha + 1]
      << ") left the domain [" << domain_.xmin << ", " << domain_.xmax << "] x [" << domain_.ymin << ", "
      << domain_.ymax << "]";
    return {Status::domain, s.str()};
  }
  return {};
}

Validity Problem::check_full(const FlatState& y) const {
  Validity v = check_step(y);
  if (v.status != Status::ok) return v;
  const Derived d = model_.derived(y);
  if (!std::isfinite(d.energy) || !std::isfinite(d.normal_force) || !std::isfinite(d.kappa1))
    return {Status::diverged, "the landscape or its derivatives are not finite at the contact point"};
  const double r = model_.params().radius;
  if (r * d.kappa1 >= 1.0) return {Status::curvature, describe("r * max curvature reached ", r * d.kappa1)};
  if (d.det_E <= 1e-12) return {Status::curvature, describe("E = C'^T C' is singular, det E = ", d.det_E)};
  if (d.normal_force <= 0.0) return {Status::lift_off, describe("the normal force fell to ", d.normal_force)};
  return {};
}

}  // namespace rb

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
    s << "the contact point (" << y[kOffsetAlpha] << ", " << y[kOffsetAlpha + 1] << ") left the domain ["
      << domain_.xmin << ", " << domain_.xmax << "] x [" << domain_.ymin << ", " << domain_.ymax << "]";
    return {Status::domain, s.str()};
  }
  return {};
}

Validity Problem::check_model(const ModelMargins& m) const {
  for (const double margin : {m.normal_force, m.det_E, m.fit_xx, m.fit_xy, m.fit_yy})
    if (!std::isfinite(margin))
      return {Status::diverged, "the landscape or its derivatives are not finite at the contact point"};
  if (!m.ball_fits()) return {Status::curvature, describe("r * max curvature reached ", m.r_kappa_max())};
  if (!m.regular()) return {Status::curvature, describe("E = C'^T C' is singular, det E = ", m.det_E)};
  if (m.normal_force <= 0.0) return {Status::lift_off, describe("the normal force fell to ", m.normal_force)};
  return {};
}

Validity Problem::check_full(const FlatState& y) const {
  const Validity v = check_step(y);
  if (v.status != Status::ok) return v;
  return check_model(model_.margins_at(y));
}

}  // namespace rb

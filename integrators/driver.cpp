#include "integrators/driver.hpp"

#include <algorithm>
#include <limits>

namespace rb {

std::vector<double> output_times_of(const Problem& problem, const RunOptions& options) {
  const double t_end = t_end_of(problem, options);
  if (!(t_end > 0.0) || !std::isfinite(t_end)) throw InputError("t_end must be a finite number > 0", "t_end");
  std::vector<double> times;
  times.reserve(options.output_times.size() + 1);
  double last = 0.0;
  for (const double t : options.output_times) {
    if (!(t > last) || t > t_end) throw InputError("output times must increase within (0, t_end]", "output_times");
    times.push_back(t);
    last = t;
  }
  if (times.empty() || times.back() < t_end) times.push_back(t_end);
  return times;
}

std::string model_stop_reason(const Validity& v, double t) {
  if (v.status != Status::curvature && v.status != Status::lift_off) return v.reason;
  char at[48];
  std::snprintf(at, sizeof at, " at t = %.9g", t);
  return v.reason + at;
}

std::string step_stop_reason(const Validity& v, double t, double h, InStep where) {
  char at[96];
  std::snprintf(at, sizeof at, " at t = %.9g (%s the step of h = %.3g from there)", t,
                where == InStep::stage ? "at a stage of" : "between the stages of", h);
  return v.reason + at;
}

Validity model_limit(const Problem& problem, const ModelMargins& m, bool non_finite) {
  Validity v = problem.check_model(m);
  if (v.status == Status::curvature || v.status == Status::lift_off) return v;
  if (non_finite && v.status == Status::diverged) return v;
  return {};
}

const Tolerances& tolerances_of(const RunOptions& options) {
  if (!options.tolerances.given()) throw InputError("an adaptive method needs rtol > 0 or atol > 0", "rtol");
  return options.tolerances;
}

Validity attainable(const Tolerances& tol, const FlatState& y0) {
  const double floor = 4.0 * std::numeric_limits<double>::epsilon();
  if (tol.rtol() >= floor || tol.atol() >= floor * y0.cwiseAbs().maxCoeff()) return {};
  char text[160];
  std::snprintf(text, sizeof text,
                "the tolerances rtol = %.3g, atol = %.3g are below the rounding of the state (%.3g relative): "
                "no step size can meet them",
                tol.rtol(), tol.atol(), floor);
  return {Status::step_underflow, text};
}

std::string underflow_message(double h, double t) {
  char text[96];
  std::snprintf(text, sizeof text, "the step size fell to %.3g at t = %.9g", h, t);
  return text;
}

StepFailure nonfinite_failure(double t, int trials, double h) {
  char text[160];
  std::snprintf(text, sizeof text, "the state is not finite beyond t = %.9g (%d trial steps past it, the last of %.3g)",
                t, trials, h);
  return StepFailure(Status::diverged, text);
}

double initial_step(const Problem& problem, const FlatState& y0, const Tolerances& tol, int order, double span,
                    Cost& cost) {
  // root-mean-square norm weighted by the tolerances
  // (kept above 0 so that atol = 0 with a zero component does not divide 0 by 0)
  const FlatState scale = (tol.atol() + tol.rtol() * y0.array().abs()).max(std::numeric_limits<double>::min()).matrix();
  auto norm = [&](const FlatState& v) { return std::sqrt((v.array() / scale.array()).square().mean()); };
  FlatState f0, f1;
  problem.flat_rhs(y0.data(), f0.data());
  const double d0 = norm(y0), d1 = norm(f0);
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, span);
  // a second derivative estimate from one explicit Euler step
  const FlatState y1 = y0 + h0 * f0;
  problem.flat_rhs(y1.data(), f1.data());
  cost.rhs_evals += 2;
  const double d2 = norm(f1 - f0) / h0;
  const double d12 = std::max(d1, d2);
  const double h1 = d12 <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / d12, 1.0 / (order + 1));
  const double h = std::min({100.0 * h0, h1, span});
  // a start where F is not finite gets a plain guess; the run reports it
  return std::isfinite(h) && h > 0.0 ? h : 1e-3 * span;
}

bool near_limit_at(const Problem& problem, const ModelMargins& m) {
  if (m.near_curvature_limit()) return true;
  // I + 2 r II = 3 I - 2 M, I = [[1 + fx^2, fx fy], [fx fy, 1 + fy^2]]
  const double xx = 1.0 + m.slope_x * m.slope_x, yy = 1.0 + m.slope_y * m.slope_y;
  const double a = 3.0 * xx - 2.0 * m.fit_xx, b = 3.0 * m.slope_x * m.slope_y - 2.0 * m.fit_xy;
  const double c = 3.0 * yy - 2.0 * m.fit_yy;
  const bool sharp_crest = (a <= 0.0) | (a * c - b * b <= 0.0);
  // N_z = 1 / sqrt(1 + fx^2 + fy^2)
  const BallParams& ball = problem.model().params();
  const bool light = m.normal_force <= 0.5 * ball.mass * ball.gravity / std::sqrt(xx + m.slope_y * m.slope_y);
  return sharp_crest | light;
}

namespace {

// The cubic Hermite interpolant of a step of h through (y0, f0), (y1, f1).
struct HermitePath {
  const FlatState &y0, &f0, &y1, &f1;
  double h;
  template <class Out>
  void at(double s, Out&& y) const {
    const double s2 = s * s, s3 = s2 * s;
    y = (2 * s3 - 3 * s2 + 1) * y0 + (h * (s3 - 2 * s2 + s)) * f0 + (3 * s2 - 2 * s3) * y1 + (h * (s3 - s2)) * f1;
  }
  Vec2 contact(double s) const {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * contact_of(y0) + (h * (s3 - 2 * s2 + s)) * f0.segment<2>(kOffsetAlpha) +
           (3 * s2 - 2 * s3) * contact_of(y1) + (h * (s3 - s2)) * f1.segment<2>(kOffsetAlpha);
  }
  // the largest distance between the contact points of n + 2 equally spaced parameters (the ends included)
  double widest_gap(int n) const {
    double widest = 0.0;
    Vec2 before = contact_of(y0);
    for (int i = 1; i <= n + 1; ++i) {
      const Vec2 p = contact(static_cast<double>(i) / (n + 1));
      widest = std::max(widest, (p - before).norm());
      before = p;
    }
    return widest;
  }
};

// How many equally spaced points between the ends put the interpolant's
// contact points at most spacing apart: travel / spacing, raised while the
// cubic's own points are further apart (its speed varies); at least
// min_points, at most kPathPointsMax; a few where travel is not finite.
int points_between(const HermitePath& path, double travel, double spacing, int min_points) {
  if (!std::isfinite(travel)) return std::max(min_points, kPathPointsMin);
  auto capped = [&](double n) {
    return static_cast<int>(std::clamp(n, static_cast<double>(min_points), static_cast<double>(kPathPointsMax)));
  };
  int n = capped(std::ceil(travel / spacing) - 1.0);
  for (int tries = 0; tries < 4 && n < kPathPointsMax; ++tries) {
    const double widest = path.widest_gap(n);
    if (!(widest > spacing)) break;  // also NaN: nothing to measure by
    n = std::max(n + 1, capped(std::ceil((n + 1) * widest / spacing) - 1.0));
  }
  return n;
}

}  // namespace

PathCheck check_step_path(const Problem& problem, const FlatState& y0, const FlatState& y1, double h, Cost& cost,
                          const PathSlope& start, double stage_speed, int min_points) {
  FlatState f0, y;
  ModelMargins m;
  PathCheck path;
  bool near = false;  // the last point evaluated is near a limit
  auto limit_at = [&](const FlatState& x, FlatState& f) -> Validity {
    problem.flat_rhs(x.data(), f.data(), m);
    ++cost.validity_checks;
    ++cost.path_checks;
    near = near_limit_at(problem, m);
    return Problem::within_model(m) ? Validity{} : model_limit(problem, m);
  };
  bool near0 = start.near;
  if (start.known) {
    f0 = start.f;
  } else {
    if ((path.limit = limit_at(y0, f0)).status != Status::ok) return path;
    near0 = near;
  }
  FlatState& f1 = path.end.f;
  if ((path.limit = limit_at(y1, f1)).status != Status::ok) return path;
  path.end.near = near;
  path.end.known = true;

  const double chord = (contact_of(y1) - contact_of(y0)).norm();
  const double speed = std::max(f0.segment<2>(kOffsetAlpha).norm(), f1.segment<2>(kOffsetAlpha).norm());
  path.travel = std::max(chord, std::abs(h) * speed);
  const double travel = std::max(path.travel, std::abs(h) * stage_speed);
  const double radius = problem.model().params().radius;
  const HermitePath cubic{y0, f0, y1, f1, h};
  const int n = points_between(cubic, travel, kPathSpacing * radius, min_points);
  // points on the stretch (s_a, s_b), at most kPathFineSpacing radii apart
  auto fine = [&](double s_a, double s_b) -> Validity {
    const double gap = (cubic.contact(s_b) - cubic.contact(s_a)).norm();
    const double wanted = std::ceil(gap / (kPathFineSpacing * radius)) - 1.0;
    const int k = std::isfinite(wanted) ? static_cast<int>(std::clamp(wanted, 0.0, double{kPathPointsMax})) : 0;
    FlatState f;
    for (int j = 1; j <= k; ++j) {
      cubic.at(s_a + (s_b - s_a) * j / (k + 1), y);
      if (const Validity v = limit_at(y, f); v.status != Status::ok) return v;
    }
    return {};
  };
  FlatState f;
  bool near_before = near0;
  for (int i = 1; i <= n + 1; ++i) {
    const double s = static_cast<double>(i) / (n + 1), s_before = static_cast<double>(i - 1) / (n + 1);
    bool near_here = path.end.near;
    if (i <= n) {
      cubic.at(s, y);
      if ((path.limit = limit_at(y, f)).status != Status::ok) return path;
      near_here = near;
    }
    if (near_before || near_here) [[unlikely]]
      if ((path.limit = fine(s_before, s)).status != Status::ok) return path;
    near_before = near_here;
  }
  return path;
}

std::string controller_of(const std::string& method_default, const RunOptions& options) {
  if (!options.controller || method_default == kConstantController || method_default == kLibraryController)
    return method_default;
  return options.controller->name;
}

}  // namespace rb

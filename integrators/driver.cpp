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

PathCheck check_step_path(const Problem& problem, const FlatState& y0, const FlatState& y1, double h, Cost& cost) {
  auto limit_of = [&](const ModelMargins& m) -> Validity {
    ++cost.validity_checks;
    return Problem::within_model(m) ? Validity{} : model_limit(problem, m);
  };
  FlatState f0, f1, y, f;
  ModelMargins m;
  PathCheck path;
  problem.flat_rhs(y0.data(), f0.data(), m);
  if ((path.limit = limit_of(m)).status != Status::ok) return path;
  problem.flat_rhs(y1.data(), f1.data(), m);
  if ((path.limit = limit_of(m)).status != Status::ok) return path;
  const double chord = (contact_of(y1) - contact_of(y0)).norm();
  const double speed = std::max(f0.segment<2>(kOffsetAlpha).norm(), f1.segment<2>(kOffsetAlpha).norm());
  path.travel = std::max(chord, std::abs(h) * speed);
  const double spacing = 0.25 * problem.model().params().radius;
  const double wanted = std::isfinite(path.travel) ? std::ceil(path.travel / spacing) : kPathPointsMax;
  const int n = static_cast<int>(std::clamp(wanted, double{kPathPointsMin}, double{kPathPointsMax}));
  for (int i = 1; i <= n; ++i) {
    const double s = static_cast<double>(i) / (n + 1), s2 = s * s, s3 = s2 * s;
    y = (2 * s3 - 3 * s2 + 1) * y0 + (h * (s3 - 2 * s2 + s)) * f0 + (3 * s2 - 2 * s3) * y1 + (h * (s3 - s2)) * f1;
    problem.flat_rhs(y.data(), f.data(), m);
    if ((path.limit = limit_of(m)).status != Status::ok) return path;
  }
  return path;
}

std::string controller_of(const std::string& method_default, const RunOptions& options) {
  if (!options.controller || method_default == kConstantController || method_default == kLibraryController)
    return method_default;
  return options.controller->name;
}

}  // namespace rb

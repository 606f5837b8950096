#include "problems/exact.hpp"

#include <gsl/gsl_mode.h>
#include <gsl/gsl_sf_ellint.h>
#include <gsl/gsl_sf_elljac.h>

#include <array>
#include <cmath>
#include <initializer_list>
#include <sstream>

#include "problems/input_error.hpp"
#include "problems/so3.hpp"

namespace rb {

// --- plane ---

PlaneSolution::PlaneSolution(double radius, const Vec2& alpha0, const Vec3& omega0, const Mat3& R0)
    : r_(radius), alpha0_(alpha0), omega0_(omega0), R0_(R0) {}

ExactState PlaneSolution::at(double t) const {
  ExactState s;
  // contact velocity = centre velocity r omega x N with N = e_z
  const Vec3 u = r_ * omega0_.cross(Vec3::UnitZ());
  s.alpha = alpha0_ + t * u.head<2>();
  s.omega = omega0_;
  s.R = so3_exp(t * omega0_, ExpSeries::below_0_1_rad) * R0_;
  s.has_rotation = true;
  return s;
}

// --- incline ---

InclineSolution::InclineSolution(double slope, double radius, double g0, const Vec2& alpha0, const Vec3& omega0,
                                 const Mat3& R0)
    : r_(radius), omega0_(omega0), R0_(R0) {
  N_ = Vec3(0.0, slope, 1.0).normalized();
  c0_ = Vec3(alpha0.x(), alpha0.y(), -slope * alpha0.y()) + r_ * N_;
  u0_ = r_ * omega0_.cross(N_);
  const Vec3 g(0.0, 0.0, -g0);
  b_ = (5.0 / (7.0 * r_)) * N_.cross(g);
  // r b x N = (5/7) (N x g) x N = (5/7) times the tangential part of g
  a_ = r_ * b_.cross(N_);
  // a fixed rotation axis: omega0 parallel to b (or one of them zero)
  has_rotation_ = omega0_.cross(b_).norm() <= 1e-12 * omega0_.norm() * b_.norm();
}

Vec3 InclineSolution::centre_at(double t) const { return c0_ + t * u0_ + (0.5 * t * t) * a_; }

ExactState InclineSolution::at(double t) const {
  ExactState s;
  const Vec3 c = centre_at(t);
  s.alpha = c.head<2>() - r_ * N_.head<2>();
  s.omega = omega0_ + t * b_;
  s.has_rotation = has_rotation_;
  if (has_rotation_) s.R = so3_exp(t * omega0_ + (0.5 * t * t) * b_, ExpSeries::below_0_1_rad) * R0_;
  return s;
}

// --- bowl pendulum ---

namespace {

double pendulum_w0(double rho, double r, double g0) { return std::sqrt(5.0 * g0 / (7.0 * (rho - r))); }

double complete_k(double k) { return gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE); }

}  // namespace

double bowl_period(double rho, double r, double g0, double theta0) {
  const double k = std::sin(0.5 * theta0);
  return 4.0 * complete_k(k) / pendulum_w0(rho, r, g0);
}

double bowl_normal_force(double m, double g0, double theta, double theta0) {
  return m * g0 * (17.0 * std::cos(theta) - 10.0 * std::cos(theta0)) / 7.0;
}

BowlPendulumSolution::BowlPendulumSolution(double rho, double radius, double g0, const Vec2& alpha0, const Mat3& R0)
    : rho_(rho), r_(radius), R0_(R0) {
  w0_ = pendulum_w0(rho, radius, g0);
  const double d = alpha0.norm();
  theta0_ = std::asin(std::min(1.0, d / rho));
  // at the bottom the swing has no direction; any e gives the same rest
  e_ = d > 0.0 ? Vec2(alpha0 / d) : Vec2(1.0, 0.0);
  k_ = std::sin(0.5 * theta0_);
  K_ = complete_k(k_);
}

double BowlPendulumSolution::theta(double t) const {
  double sn, cn, dn;
  gsl_sf_elljac_e(K_ - w0_ * t, k_ * k_, &sn, &cn, &dn);
  return 2.0 * std::asin(k_ * sn);
}

double BowlPendulumSolution::theta_dot(double t) const {
  double sn, cn, dn;
  gsl_sf_elljac_e(K_ - w0_ * t, k_ * k_, &sn, &cn, &dn);
  return -2.0 * k_ * w0_ * cn;
}

double BowlPendulumSolution::period() const { return 4.0 * K_ / w0_; }

ExactState BowlPendulumSolution::at(double t) const {
  const double th = theta(t);
  // e1 = e, e3 = z, e2 = e3 x e1: the ball turns about e2
  const Vec3 e2(-e_.y(), e_.x(), 0.0);
  const double ratio = (rho_ - r_) / r_;
  ExactState s;
  s.alpha = rho_ * std::sin(th) * e_;
  s.omega = ratio * theta_dot(t) * e2;
  s.R = so3_exp(ratio * (th - theta0_) * e2, ExpSeries::below_0_1_rad) * R0_;
  s.has_rotation = true;
  return s;
}

// --- from a scene ---

namespace {

std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

double required_param(const Scene& scene, const char* name, const std::string& why) {
  const auto it = scene.params.find(name);
  if (it == scene.params.end())
    throw InputError("'" + scene.exact + "' needs the param '" + name + "' (" + why + ") under \"params\"", "exact");
  return it->second;
}

}  // namespace

std::vector<Vec2> landscape_sample_points(double scale, const Vec2& start) {
  std::vector<Vec2> p;
  for (const auto& [x, y] : std::initializer_list<std::pair<double, double>>{
           {0.0, 0.0}, {0.3, -0.2}, {-0.55, 0.4}, {0.1, 0.7}, {-0.6, -0.5}, {0.8, 0.05}})
    p.emplace_back(scale * x, scale * y);
  p.push_back(start);
  return p;
}

void expect_landscape(const RollingBall& model, const std::vector<Vec2>& points, const LandscapeJet& want,
                      const std::string& what, const std::string& key) {
  for (const Vec2& p : points) {
    const Jet2<double> got = model.landscape().at(p.x(), p.y());
    const std::array<double, 6> w = want(p.x(), p.y());
    const std::array<double, 6> g = {got.f, got.fx, got.fy, got.fxx, got.fxy, got.fyy};
    for (int i = 0; i < 6; ++i)
      if (!(std::abs(g[i] - w[i]) <= 1e-9 * (1.0 + std::abs(w[i]))))
        throw InputError("the landscape is not " + what + " (at x = " + num(p.x()) + ", y = " + num(p.y()) + ")", key);
  }
}

LandscapeJet spherical_bowl(double rho) {
  return [rho](double x, double y) {
    const double g = std::sqrt(rho * rho - x * x - y * y), g3 = g * g * g;
    return std::array<double, 6>{rho - g, x / g, y / g, 1.0 / g + x * x / g3, x * y / g3, 1.0 / g + y * y / g3};
  };
}

std::shared_ptr<const ExactSolution> make_exact(const Scene& scene, const RollingBall& model) {
  const std::string& name = scene.exact;
  if (name == "none") return nullptr;
  if (scene.ball.inertia)
    throw InputError("'" + name + "' is a closed form of the homogeneous ball; a scene with ball.inertia has none",
                     "exact");
  const double r = scene.ball.radius, g0 = scene.gravity;
  const Vec2 a0 = scene.start.contact;
  const Vec3 omega0 = start_omega(scene, model);
  const Mat3 R0 = start_rotation(scene);

  if (name == "plane") {
    expect_landscape(
        model, landscape_sample_points(1.0, a0), [](double, double) { return std::array<double, 6>{}; },
        "the plane f = 0", "exact");
    return std::make_shared<PlaneSolution>(r, a0, omega0, R0);
  }
  if (name == "incline") {
    const double s = required_param(scene, "s", "the slope of f = -s*y");
    expect_landscape(
        model, landscape_sample_points(1.0, a0),
        [s](double, double y) { return std::array<double, 6>{-s * y, 0.0, -s, 0.0, 0.0, 0.0}; },
        "the incline f = -s*y with s = " + num(s), "exact");
    return std::make_shared<InclineSolution>(s, r, g0, a0, omega0, R0);
  }
  if (name == "bowl-pendulum") {
    const double rho = required_param(scene, "rho", "the radius of the bowl f = rho - sqrt(rho^2 - x^2 - y^2)");
    if (!(rho > r)) throw InputError("the bowl's radius rho = " + num(rho) + " must exceed the ball's", "exact");
    if (!(a0.norm() < rho)) throw InputError("the start contact lies outside the bowl", "exact");
    expect_landscape(model, landscape_sample_points(0.9 * rho / std::sqrt(2.0), a0), spherical_bowl(rho),
                     "the spherical bowl f = rho - sqrt(rho^2 - x^2 - y^2) with rho = " + num(rho), "exact");
    if (omega0.norm() != 0.0)
      throw InputError("'bowl-pendulum' starts at rest; the start's omega (or velocity and spin) must be 0", "exact");
    return std::make_shared<BowlPendulumSolution>(rho, r, g0, a0, R0);
  }
  throw InputError("unknown exact solution '" + name + "'", "exact");
}

std::vector<std::string> exact_names() { return {"bowl-pendulum", "incline", "plane"}; }

}  // namespace rb

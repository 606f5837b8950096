#include "problems/invariants.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "problems/exact.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"

namespace rb {

namespace {

// k / (k + 1) for the homogeneous ball's k = 2/5: Routh's ODE's coupling
constexpr double kCoupling = 2.0 / 7.0;

// omega = T^-1 v of the homogeneous ball, T^-1 = 5 / (7 m r^2) (I + 5/2 N N^T)
Vec3 homogeneous_omega(const Vec3& v, const Vec3& N, double r, double m) {
  return (5.0 / (7.0 * m * r * r)) * (v + 2.5 * N * N.dot(v));
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

}  // namespace

void hypergeometric_2f1(double a, double b, double c, double x, double* F, double* xF_prime) {
  double term = 1.0, sum = 1.0, dsum = 0.0;
  for (int n = 0; n < 100000; ++n) {
    term *= (a + n) * (b + n) / ((c + n) * (n + 1.0)) * x;
    const double before = sum, dbefore = dsum;
    sum += term;
    dsum += (n + 1.0) * term;
    if (sum == before && dsum == dbefore) break;
  }
  *F = sum;
  *xF_prime = dsum;
}

// --- Routh in the paraboloid ---

RouthParaboloid::RouthParaboloid(double a, double radius, double mass)
    : a_(a), r_(radius), m_(mass), eps_(2.0 * a * radius) {}

RouthParaboloid::Solutions RouthParaboloid::solutions(double c) const {
  Solutions s{};
  const double x = eps_ * c;
  for (int i = 0; i < 2; ++i) {
    const double l = (i == 0 ? 1.0 : -1.0) * std::sqrt(kCoupling);
    double F = 0.0, xF = 0.0;
    hypergeometric_2f1(l, l + 2.0, 2.0 * l + 1.0, x, &F, &xF);
    const double cl = std::pow(c, l);
    s.w[i] = cl * F;
    s.u[i] = -(1.0 - x) * (1.0 - x) * cl * (l * F + xF) / (2.0 * a_);
  }
  return s;
}

void RouthParaboloid::at(const FlatState& y, double* value, double* magnitude) const {
  const Vec2 p = contact_of(y);
  const double rho2 = p.squaredNorm();
  const Vec3 N = Vec3(-2.0 * a_ * p.x(), -2.0 * a_ * p.y(), 1.0).normalized();
  const Vec3 w = homogeneous_omega(momentum_of(y), N, r_, m_);
  const double c = N.z();
  // u = R_c (omega . t): R_c the centre's distance from the axis, t the meridian's unit tangent
  const double u = (1.0 - eps_ * c) * c * (p.x() * w.x() + p.y() * w.y() + 2.0 * a_ * rho2 * w.z());
  const double wn = w.dot(N);
  const Solutions s = solutions(c);
  value[0] = u * s.w[1] - wn * s.u[1];
  value[1] = wn * s.u[0] - u * s.w[0];
  magnitude[0] = std::abs(u * s.w[1]) + std::abs(wn * s.u[1]);
  magnitude[1] = std::abs(wn * s.u[0]) + std::abs(u * s.w[0]);
}

// --- Routh in the spherical bowl ---

RouthSphere::RouthSphere(double rho, double radius, double mass) : rho_(rho), r_(radius), m_(mass) {}

void RouthSphere::at(const FlatState& y, double* value, double* magnitude) const {
  const Vec2 p = contact_of(y);
  const double rho2 = p.squaredNorm();
  const double g = std::sqrt(rho_ * rho_ - rho2);
  const Vec3 N = Vec3(-p.x(), -p.y(), g) / rho_;
  const Vec3 w = homogeneous_omega(momentum_of(y), N, r_, m_);
  const double c = N.z(), wn = w.dot(N);
  // u / (rho - r) = R_c (omega . t) / (rho - r)
  const double u = (c * (p.x() * w.x() + p.y() * w.y()) + rho2 * w.z() / rho_) / rho_;
  value[0] = wn;
  magnitude[0] = w.norm();
  value[1] = u + kCoupling * c * wn;
  magnitude[1] = std::abs(u) + kCoupling * std::abs(c * wn);
}

// --- the Chaplygin ball on a plane ---

void ChaplyginPlane::at(const FlatState& y, double* value, double* magnitude) const {
  const Mat3 R = rotation_of(y);
  const Vec3 M = R.transpose() * momentum_of(y);
  const Vec3 gamma = R.transpose() * Vec3::UnitZ();
  value[0] = M.squaredNorm();
  magnitude[0] = value[0];
  value[1] = M.dot(gamma);
  magnitude[1] = M.norm() * gamma.norm();
}

// --- from a scene ---

namespace {

double required_param(const Scene& scene, const std::string& family, const char* name, const std::string& why) {
  const auto it = scene.params.find(name);
  if (it == scene.params.end())
    throw InputError("'" + family + "' needs the param '" + name + "' (" + why + ") under \"params\"", "invariants");
  return it->second;
}

void expect_homogeneous(const Scene& scene, const std::string& family) {
  if (scene.ball.inertia)
    throw InputError("'" + family + "' holds for the homogeneous ball; a scene with ball.inertia does not have it",
                     "invariants");
}

std::shared_ptr<const FirstIntegrals> make_one(const Scene& scene, const RollingBall& model, const std::string& name) {
  const double r = scene.ball.radius, m = scene.ball.mass;
  const Vec2 a0 = scene.start.contact;
  if (name == "routh-paraboloid") {
    expect_homogeneous(scene, name);
    const double a = required_param(scene, name, "a", "the paraboloid f = a*(x^2 + y^2)");
    if (!(a > 0.0)) throw InputError("'routh-paraboloid' needs a bowl, a > 0, not a = " + num(a), "invariants");
    if (!(2.0 * a * r < 1.0))
      throw InputError(
          "'routh-paraboloid' needs the ball to fit the bottom of the bowl, 2 a r < 1, not " + num(2.0 * a * r),
          "invariants");
    expect_landscape(
        model, landscape_sample_points(1.0, a0),
        [a](double x, double y) {
          return std::array<double, 6>{a * (x * x + y * y), 2.0 * a * x, 2.0 * a * y, 2.0 * a, 0.0, 2.0 * a};
        },
        "the paraboloid f = a*(x^2 + y^2) with a = " + num(a), "invariants");
    return std::make_shared<RouthParaboloid>(a, r, m);
  }
  if (name == "routh-sphere") {
    expect_homogeneous(scene, name);
    const double rho = required_param(scene, name, "rho", "the radius of the bowl f = rho - sqrt(rho^2 - x^2 - y^2)");
    if (!(rho > r)) throw InputError("the bowl's radius rho = " + num(rho) + " must exceed the ball's", "invariants");
    expect_landscape(model, landscape_sample_points(0.9 * rho / std::sqrt(2.0), a0), spherical_bowl(rho),
                     "the spherical bowl f = rho - sqrt(rho^2 - x^2 - y^2) with rho = " + num(rho), "invariants");
    return std::make_shared<RouthSphere>(rho, r, m);
  }
  if (name == "chaplygin-plane") {
    const double f0 = model.landscape().at(a0.x(), a0.y()).f;
    expect_landscape(
        model, landscape_sample_points(1.0, a0), [f0](double, double) { return std::array<double, 6>{f0}; },
        "a horizontal plane f = const", "invariants");
    return std::make_shared<ChaplyginPlane>();
  }
  throw InputError("unknown invariant '" + name + "'", "invariants");
}

}  // namespace

std::vector<std::shared_ptr<const FirstIntegrals>> make_invariants(const Scene& scene, const RollingBall& model) {
  std::vector<std::shared_ptr<const FirstIntegrals>> out;
  for (const std::string& name : scene.invariants) out.push_back(make_one(scene, model, name));
  return out;
}

std::string_view kind_name(IntegralKind kind) { return kind == IntegralKind::kinematic ? "kinematic" : "dynamical"; }

std::vector<std::string> invariant_names() { return {"chaplygin-plane", "routh-paraboloid", "routh-sphere"}; }

}  // namespace rb

#pragma once
// Closed-form solutions of the rolling ball (docs/model.md, "Results with a closed
// form"), the anchors of the tests and the exact references of the reports.
// Scenes name them under "exact"; make_exact checks that the scene's
// landscape and start are the ones the solution assumes.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "problems/problem.hpp"
#include "problems/scene.hpp"

namespace rb {

// f = 0: the contact moves on a straight line at the constant velocity
// r omega0 x N, omega is constant and R(t) = exp(t hat(omega0)) R0.
class PlaneSolution final : public ExactSolution {
 public:
  PlaneSolution(double radius, const Vec2& alpha0, const Vec3& omega0, const Mat3& R0);
  std::string name() const override { return "plane"; }
  ExactState at(double t) const override;

 private:
  double r_;
  Vec2 alpha0_;
  Vec3 omega0_;
  Mat3 R0_;
};

// f = -s y: N is constant, omega(t) = omega0 + t b with b = 5 / (7 r) N x g,
// and the centre accelerates down the fall line at (5/7) g0 sin(theta),
// tan(theta) = s. R(t) is known only when omega0 is parallel to b (or b = 0).
class InclineSolution final : public ExactSolution {
 public:
  InclineSolution(double slope, double radius, double g0, const Vec2& alpha0, const Vec3& omega0, const Mat3& R0);
  std::string name() const override { return "incline"; }
  ExactState at(double t) const override;

  // The centre c(t) = c0 + u0 t + a t^2 / 2, world frame.
  Vec3 centre_at(double t) const;
  // The centre's acceleration a = (5/7) (g - (g . N) N), world frame.
  const Vec3& centre_acceleration() const { return a_; }
  bool has_rotation() const { return has_rotation_; }

 private:
  double r_;
  Vec3 N_, c0_, u0_, a_, omega0_, b_;
  Mat3 R0_;
  bool has_rotation_;
};

// f = rho - sqrt(rho^2 - x^2 - y^2), a start at rest at polar angle theta0
// from the bottom, the contact at rho sin(theta0) e: a pendulum of length
// rho - r in the vertical plane through e with w0^2 = 5 g0 / (7 (rho - r)),
// theta(t) = 2 asin(k sn(K(k) - w0 t, k)), k = sin(theta0 / 2).
class BowlPendulumSolution final : public ExactSolution {
 public:
  BowlPendulumSolution(double rho, double radius, double g0, const Vec2& alpha0, const Mat3& R0);
  std::string name() const override { return "bowl-pendulum"; }
  ExactState at(double t) const override;

  double theta0() const { return theta0_; }
  double theta(double t) const;                 // polar angle of the contact (and the centre), signed along e
  double theta_dot(double t) const;             // its rate, 1/s
  double period() const;                        // 4 K(k) / w0, s (infinite when g0 = 0)
  const Vec2& direction() const { return e_; }  // e, the unit swing direction in the (x, y) plane

 private:
  double rho_, r_, w0_, theta0_, k_, K_;
  Vec2 e_;
  Mat3 R0_;
};

// The period 4 K(k) / w0 of the bowl pendulum, s.
double bowl_period(double rho, double r, double g0, double theta0);
// The normal force F . N = m g0 (17 cos(theta) - 10 cos(theta0)) / 7 at angle
// theta of a swing from rest at theta0, N.
double bowl_normal_force(double m, double g0, double theta, double theta0);

// The exact solution a scene names, or nullptr for "none". Throws InputError
// (key "exact") when the scene's landscape, params or start do not fit it.
std::shared_ptr<const ExactSolution> make_exact(const Scene& scene, const RollingBall& model);

// The names a scene may give under "exact" besides "none", sorted.
std::vector<std::string> exact_names();

// A landscape a closed form (or a first integral) assumes: f, f_x, f_y,
// f_xx, f_xy, f_yy at (x, y).
using LandscapeJet = std::function<std::array<double, 6>(double, double)>;

// Points where a landscape is compared with the one assumed, scaled by a
// length (the bowl's radius), plus the start contact.
std::vector<Vec2> landscape_sample_points(double scale, const Vec2& start);

// Throws InputError (at key) unless f, grad f and Hess f of the model's
// landscape equal want at every point, relative to 1 + |value|; what names
// the landscape assumed in the message.
void expect_landscape(const RollingBall& model, const std::vector<Vec2>& points, const LandscapeJet& want,
                      const std::string& what, const std::string& key);

// The spherical bowl f = rho - sqrt(rho^2 - x^2 - y^2).
LandscapeJet spherical_bowl(double rho);

}  // namespace rb

#pragma once
// First integrals beyond the energy (docs/model.md, "Invariants beyond the
// energy"): what a scene keeps because of its landscape and its ball, named
// under the scene's "invariants" and checked against both on load, so that
// a scene never claims an integral its landscape does not have.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "problems/rolling_ball.hpp"

namespace rb {

struct Scene;

// What keeping an integral shows (docs/model.md, "Which integrals show
// structure"). dynamical: a first integral of the flow that a method keeps
// only by its structure or its accuracy. kinematic: one that every method
// keeps by the form of the equations alone, a function of a linear integral
// whose rate is identically 0 in the right-hand side (which every
// Runge-Kutta step keeps to rounding) and of R^T R (which a Lie-group method
// keeps to rounding, and whose drift is a flat method's rotation defect):
// keeping it is no evidence of structure preservation, and the findings
// never cite it as such.
enum class IntegralKind { dynamical, kinematic };

// The report's spelling: "dynamical", "kinematic".
std::string_view kind_name(IntegralKind kind);

// One declared family of first integrals, each a scalar function of the
// state that the exact flow keeps constant.
class FirstIntegrals {
 public:
  virtual ~FirstIntegrals() = default;
  // The name a scene gives under "invariants": "routh-paraboloid", ...
  virtual std::string name() const = 0;
  // The integrals' short names, in the order at() fills them: "J1", "J2".
  virtual std::vector<std::string> quantities() const = 0;
  // Each integral's kind, in the order of quantities().
  virtual std::vector<IntegralKind> kinds() const = 0;
  // Each integral's value at y, and its magnitude there: the sum of the
  // absolute values of the terms it is made of, the scale its rounding
  // errors are relative to.
  virtual void at(const FlatState& y, double* value, double* magnitude) const = 0;
};

// Routh's two integrals of a homogeneous ball (inertia 2/5 m r^2 about its
// centre) in the paraboloid f = a (x^2 + y^2), a > 0, 2 a r < 1: with
// c = N_z, eps = 2 a r, x = eps c, u = (1 - eps c) c (x w_x + y w_y +
// 2 a rho^2 w_z) and w_n = omega . N, the solutions w_i = c^l F(l, l + 2;
// 2l + 1; x), u_i = -(1 - x)^2 c^l (l F + x F') / (2a) for l = +-sqrt(2/7)
// give J1 = u w_2 - w_n u_2 and J2 = w_n u_1 - u w_1.
class RouthParaboloid final : public FirstIntegrals {
 public:
  RouthParaboloid(double a, double radius, double mass);
  std::string name() const override { return "routh-paraboloid"; }
  std::vector<std::string> quantities() const override { return {"J1", "J2"}; }
  std::vector<IntegralKind> kinds() const override { return {IntegralKind::dynamical, IntegralKind::dynamical}; }
  void at(const FlatState& y, double* value, double* magnitude) const override;

  // (w_i, u_i) for l = +sqrt(2/7) (i = 0) and -sqrt(2/7) (i = 1) at c = N_z.
  struct Solutions {
    double w[2], u[2];
  };
  Solutions solutions(double c) const;

 private:
  double a_, r_, m_, eps_;
};

// A homogeneous ball in the spherical bowl f = rho - sqrt(rho^2 - x^2 - y^2):
// omega . N, and Routh's second integral, divided by (rho - r),
// [c (x w_x + y w_y) + (x^2 + y^2) w_z / rho] / rho + (2/7) c omega . N with c = N_z.
// The second is identically w_z - (5/7) c omega . N = (5/7) v_z / (m r^2),
// and v_z's rate is identically 0 in a spherical bowl (N' alpha' is
// parallel to omega x N there): it is kinematic, kept by every method (Euler
// with a 300 % energy error keeps it to 1e-15). omega . N is dynamical.
class RouthSphere final : public FirstIntegrals {
 public:
  RouthSphere(double rho, double radius, double mass);
  std::string name() const override { return "routh-sphere"; }
  std::vector<std::string> quantities() const override { return {"omega.N", "J"}; }
  std::vector<IntegralKind> kinds() const override { return {IntegralKind::dynamical, IntegralKind::kinematic}; }
  void at(const FlatState& y, double* value, double* magnitude) const override;

 private:
  double rho_, r_, m_;
};

// Any ball (the Chaplygin ball included) on a horizontal plane: the
// angular momentum about the contact K = T omega = v is constant in space;
// in the body frame, M = R^T K and gamma = R^T N, the integrals |M|^2 and
// M . gamma, which R's drift off SO(3) moves (K itself is the state's v,
// whose rate is exactly 0 here: every method keeps it). Both are kinematic:
// with v kept, |M|^2 = v^T R R^T v and M . gamma = v^T R R^T N are |v|^2 and
// v . N wherever R is a rotation, so every Lie-group method keeps them
// (exp-euler to 3e-14 with a 7e-2 energy error), and a flat method's error
// in them is its rotation defect's.
class ChaplyginPlane final : public FirstIntegrals {
 public:
  ChaplyginPlane() = default;
  std::string name() const override { return "chaplygin-plane"; }
  std::vector<std::string> quantities() const override { return {"K.K", "K.N"}; }
  std::vector<IntegralKind> kinds() const override { return {IntegralKind::kinematic, IntegralKind::kinematic}; }
  void at(const FlatState& y, double* value, double* magnitude) const override;
};

// The families a scene declares, each checked against its landscape, ball
// and params; throws InputError (key "invariants") when one does not fit.
std::vector<std::shared_ptr<const FirstIntegrals>> make_invariants(const Scene& scene, const RollingBall& model);

// The names a scene may give under "invariants", sorted.
std::vector<std::string> invariant_names();

// The hypergeometric series F(a, b; c; x) and x F'(x), |x| < 1, summed
// until the terms stop changing them (exact to rounding).
void hypergeometric_2f1(double a, double b, double c, double x, double* F, double* xF_prime);

}  // namespace rb

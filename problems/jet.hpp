#pragma once
// A second-order forward-mode number: a value with its gradient and Hessian
// with respect to the contact coordinates (x, y). The formula evaluator runs
// its program on these, so one pass gives f, grad f and Hess f exactly (up to
// rounding), as the rolling-ball equations need.
//
// T is double in the step loop and an Eigen::AutoDiffScalar when the
// integrators want the Jacobian of the right-hand side; so every math call is
// written `using std::sin; sin(u)` (ADL finds Eigen's overloads), and the few
// functions Eigen's AutoDiff lacks or implements with heap allocation (atan,
// atan2, hypot, pow with a variable exponent) are lifted from double below.
// Nothing here allocates.
//
// The operators and functions are hidden friends: they are found through
// Jet2 arguments only, so they never hide ::sqrt(double) and friends from
// other code in namespace rb.
#include <cmath>
#include <type_traits>

namespace rb {

namespace jet_detail {

// Whether T's own functions give g(u) exactly (double, and the symbolic
// scalar that lowers a formula to a tape), rather than through the value
// and first derivative as for a first-order AD number.
template <class T>
inline constexpr bool is_direct_v = std::is_arithmetic_v<T>;

// A constant's value part: T(c), except for the symbolic scalar of the
// tape lowering, which marks it as a formula's number (formula.cpp): a
// value computes c * u as value() does, NaN included, where a jet's own
// zero derivative may absorb a product.
template <class T>
T value_constant(double c) {
  return T(c);
}

// The double value of an AD number (the number itself for double).
inline double value_of(double u) { return u; }
template <class T>
auto value_of(const T& u) -> decltype(u.value()) {
  return u.value();
}

// g(u) for an AD number from g(u0) and g'(u0): value g(u0) exactly, first
// derivatives g'(u0) u'. The AD numbers in use are first order, so this is
// all of g.
template <class T>
T lift(double g0, const T& u, double g1) {
  return T(g0) + (u - T(value_of(u))) * g1;
}

// u^n for an integer n >= 0 by squaring; the same sequence of products in
// the value and the derivative paths, so eval().f equals value() exactly.
template <class T>
T ipow(T b, unsigned n) {
  T r(1.0);
  while (n != 0) {
    if (n & 1u) r = r * b;
    n >>= 1;
    if (n != 0) b = b * b;
  }
  return r;
}

template <class T>
T atan_of(const T& u) {
  if constexpr (is_direct_v<T>) {
    using std::atan;
    return atan(u);
  } else {
    const double u0 = value_of(u);
    return lift(std::atan(u0), u, 1.0 / (1.0 + u0 * u0));
  }
}

template <class T>
T atan2_of(const T& a, const T& b) {
  if constexpr (is_direct_v<T>) {
    using std::atan2;
    return atan2(a, b);
  } else {
    // Eigen's atan2 returns a dynamically sized derivative (allocates)
    const double a0 = value_of(a), b0 = value_of(b), d0 = a0 * a0 + b0 * b0;
    return T(std::atan2(a0, b0)) + ((a - T(a0)) * b0 - (b - T(b0)) * a0) / d0;
  }
}

template <class T>
T hypot_of(const T& a, const T& b) {
  if constexpr (is_direct_v<T>) {
    using std::hypot;
    return hypot(a, b);
  } else {
    const double a0 = value_of(a), b0 = value_of(b), h0 = std::hypot(a0, b0);
    return T(h0) + ((a - T(a0)) * a0 + (b - T(b0)) * b0) / h0;
  }
}

// u^v with both variable.
template <class T>
T pow_of(const T& u, const T& v) {
  if constexpr (is_direct_v<T>) {
    using std::pow;
    return pow(u, v);
  } else {
    const double u0 = value_of(u), v0 = value_of(v), p0 = std::pow(u0, v0);
    return T(p0) + (u - T(u0)) * (v0 * p0 / u0) + (v - T(v0)) * (p0 * std::log(u0));
  }
}

// c^v with a constant base c.
template <class T>
T pow_base_of(double c, const T& v) {
  if constexpr (is_direct_v<T>) {
    using std::pow;
    return pow(c, v);
  } else {
    const double p0 = std::pow(c, value_of(v));
    return lift(p0, v, p0 * std::log(c));
  }
}

}  // namespace jet_detail

template <class T>
struct Jet2 {
  T f, fx, fy, fxx, fxy, fyy;

  static Jet2 constant(double c) { return {jet_detail::value_constant<T>(c), T(0.0), T(0.0), T(0.0), T(0.0), T(0.0)}; }
  static Jet2 variable_x(const T& x) { return {x, T(1.0), T(0.0), T(0.0), T(0.0), T(0.0)}; }
  static Jet2 variable_y(const T& y) { return {y, T(0.0), T(1.0), T(0.0), T(0.0), T(0.0)}; }

  // g(u) from g, g' and g'' at u's value: grad g' grad u, Hessian
  // g' Hess u + g'' grad u grad u^T.
  static Jet2 chain(const Jet2& u, const T& g, const T& g1, const T& g2) {
    return {g,
            g1 * u.fx,
            g1 * u.fy,
            g1 * u.fxx + g2 * u.fx * u.fx,
            g1 * u.fxy + g2 * u.fx * u.fy,
            g1 * u.fyy + g2 * u.fy * u.fy};
  }

  // -- arithmetic --------------------------------------------------------

  friend Jet2 operator-(const Jet2& u) { return {-u.f, -u.fx, -u.fy, -u.fxx, -u.fxy, -u.fyy}; }

  friend Jet2 operator+(const Jet2& a, const Jet2& b) {
    return {a.f + b.f, a.fx + b.fx, a.fy + b.fy, a.fxx + b.fxx, a.fxy + b.fxy, a.fyy + b.fyy};
  }
  friend Jet2 operator-(const Jet2& a, const Jet2& b) {
    return {a.f - b.f, a.fx - b.fx, a.fy - b.fy, a.fxx - b.fxx, a.fxy - b.fxy, a.fyy - b.fyy};
  }
  friend Jet2 operator*(const Jet2& a, const Jet2& b) {
    return {a.f * b.f,
            a.fx * b.f + a.f * b.fx,
            a.fy * b.f + a.f * b.fy,
            a.fxx * b.f + T(2.0) * a.fx * b.fx + a.f * b.fxx,
            a.fxy * b.f + a.fx * b.fy + a.fy * b.fx + a.f * b.fxy,
            a.fyy * b.f + T(2.0) * a.fy * b.fy + a.f * b.fyy};
  }
  // q = a / b from a = q b: q' = (a' - q b') / b, q'' = (a'' - 2 q' b' - q b'') / b;
  // the value is a.f / b.f, as in the plain evaluation.
  friend Jet2 operator/(const Jet2& a, const Jet2& b) {
    const T inv = T(1.0) / b.f;
    const T q = a.f / b.f;
    const T qx = (a.fx - q * b.fx) * inv;
    const T qy = (a.fy - q * b.fy) * inv;
    return {q,
            qx,
            qy,
            (a.fxx - T(2.0) * qx * b.fx - q * b.fxx) * inv,
            (a.fxy - qx * b.fy - qy * b.fx - q * b.fxy) * inv,
            (a.fyy - T(2.0) * qy * b.fy - q * b.fyy) * inv};
  }

  // with a double constant c: no cross terms, and c stays a double for AD
  friend Jet2 operator+(const Jet2& u, double c) { return {u.f + c, u.fx, u.fy, u.fxx, u.fxy, u.fyy}; }
  friend Jet2 operator+(double c, const Jet2& u) { return {c + u.f, u.fx, u.fy, u.fxx, u.fxy, u.fyy}; }
  friend Jet2 operator-(const Jet2& u, double c) { return {u.f - c, u.fx, u.fy, u.fxx, u.fxy, u.fyy}; }
  friend Jet2 operator-(double c, const Jet2& u) { return {c - u.f, -u.fx, -u.fy, -u.fxx, -u.fxy, -u.fyy}; }
  friend Jet2 operator*(const Jet2& u, double c) {
    return {u.f * c, u.fx * c, u.fy * c, u.fxx * c, u.fxy * c, u.fyy * c};
  }
  friend Jet2 operator*(double c, const Jet2& u) { return u * c; }
  friend Jet2 operator/(const Jet2& u, double c) {
    return {u.f / c, u.fx / c, u.fy / c, u.fxx / c, u.fxy / c, u.fyy / c};
  }
  friend Jet2 operator/(double c, const Jet2& u) {
    const T g = c / u.f;
    const T g1 = -g / u.f;
    return chain(u, g, g1, T(-2.0) * g1 / u.f);
  }

  // -- powers ------------------------------------------------------------

  // u^n, integer n: exact at u = 0 (x^2 at 0 has slope 0 and curvature 2).
  friend Jet2 powi(const Jet2& u, int n) {
    using jet_detail::ipow;
    if (n == 0) return constant(1.0);
    if (n == 1) return u;
    if (n < 0) {
      const Jet2 r = powi(u, -n);
      const T g = T(1.0) / r.f;
      return chain(r, g, -g * g, T(2.0) * g * g * g);
    }
    const unsigned m = static_cast<unsigned>(n);
    return chain(u, ipow(u.f, m), double(n) * ipow(u.f, m - 1), double(n) * double(n - 1) * ipow(u.f, m - 2));
  }
  // u^c, constant real c.
  friend Jet2 pow(const Jet2& u, double c) {
    using std::pow;
    const T p2 = pow(u.f, c - 2.0);
    return chain(u, pow(u.f, c), c * p2 * u.f, c * (c - 1.0) * p2);
  }
  // c^v, constant base: (c^v)' = c^v log(c) v'.
  friend Jet2 pow(double c, const Jet2& v) {
    const double l = std::log(c);
    const T g = jet_detail::pow_base_of(c, v.f);
    const T g1 = g * l;
    return chain(v, g, g1, g1 * l);
  }
  // u^v = exp(v log u): defined for u > 0.
  friend Jet2 pow(const Jet2& u, const Jet2& v) {
    const Jet2 w = v * log(u);
    const T g = jet_detail::pow_of(u.f, v.f);
    return chain(w, g, g, g);
  }

  // -- elementary functions ----------------------------------------------

  friend Jet2 sin(const Jet2& u) {
    using std::cos, std::sin;
    const T s = sin(u.f);
    return chain(u, s, cos(u.f), -s);
  }
  friend Jet2 cos(const Jet2& u) {
    using std::cos, std::sin;
    const T c = cos(u.f);
    return chain(u, c, -sin(u.f), -c);
  }
  friend Jet2 tan(const Jet2& u) {
    using std::tan;
    const T t = tan(u.f);
    const T g1 = T(1.0) + t * t;
    return chain(u, t, g1, T(2.0) * t * g1);
  }
  // asin' = 1 / sqrt(1 - u^2), asin'' = u / (1 - u^2)^(3/2)
  friend Jet2 asin(const Jet2& u) {
    using std::asin, std::sqrt;
    const T s = T(1.0) / sqrt(T(1.0) - u.f * u.f);
    return chain(u, asin(u.f), s, u.f * s * s * s);
  }
  friend Jet2 acos(const Jet2& u) {
    using std::acos, std::sqrt;
    const T s = T(1.0) / sqrt(T(1.0) - u.f * u.f);
    return chain(u, acos(u.f), -s, -(u.f * s * s * s));
  }
  friend Jet2 atan(const Jet2& u) {
    const T g1 = T(1.0) / (T(1.0) + u.f * u.f);
    return chain(u, jet_detail::atan_of(u.f), g1, T(-2.0) * u.f * g1 * g1);
  }
  friend Jet2 sinh(const Jet2& u) {
    using std::cosh, std::sinh;
    const T s = sinh(u.f);
    return chain(u, s, cosh(u.f), s);
  }
  friend Jet2 cosh(const Jet2& u) {
    using std::cosh, std::sinh;
    const T c = cosh(u.f);
    return chain(u, c, sinh(u.f), c);
  }
  friend Jet2 tanh(const Jet2& u) {
    using std::tanh;
    const T t = tanh(u.f);
    const T g1 = T(1.0) - t * t;
    return chain(u, t, g1, T(-2.0) * t * g1);
  }
  friend Jet2 exp(const Jet2& u) {
    using std::exp;
    const T e = exp(u.f);
    return chain(u, e, e, e);
  }
  friend Jet2 log(const Jet2& u) {
    using std::log;
    const T inv = T(1.0) / u.f;
    return chain(u, log(u.f), inv, -(inv * inv));
  }
  // sqrt' = 1 / (2 s), sqrt'' = -1 / (4 s u)
  friend Jet2 sqrt(const Jet2& u) {
    using std::sqrt;
    const T s = sqrt(u.f);
    const T g1 = T(0.5) / s;
    return chain(u, s, g1, T(-0.5) * g1 / u.f);
  }

  // atan2(a, b): grad = (b grad a - a grad b) / D, D = a^2 + b^2;
  // d_j theta_i = (b_j a_i + b a_ij - a_j b_i - a b_ij - theta_i D_j) / D.
  friend Jet2 atan2(const Jet2& a, const Jet2& b) {
    const T inv = T(1.0) / (a.f * a.f + b.f * b.f);
    const T tx = (b.f * a.fx - a.f * b.fx) * inv;
    const T ty = (b.f * a.fy - a.f * b.fy) * inv;
    const T dx = T(2.0) * (a.f * a.fx + b.f * b.fx);
    const T dy = T(2.0) * (a.f * a.fy + b.f * b.fy);
    return {jet_detail::atan2_of(a.f, b.f),
            tx,
            ty,
            (b.f * a.fxx - a.f * b.fxx - tx * dx) * inv,
            (b.fy * a.fx + b.f * a.fxy - a.fy * b.fx - a.f * b.fxy - tx * dy) * inv,
            (b.f * a.fyy - a.f * b.fyy - ty * dy) * inv};
  }
  // hypot(a, b) = h: grad = (a grad a + b grad b) / h;
  // h_ij = (a_i a_j + a a_ij + b_i b_j + b b_ij - h_i h_j) / h.
  friend Jet2 hypot(const Jet2& a, const Jet2& b) {
    const T h = jet_detail::hypot_of(a.f, b.f);
    const T inv = T(1.0) / h;
    const T hx = (a.f * a.fx + b.f * b.fx) * inv;
    const T hy = (a.f * a.fy + b.f * b.fy) * inv;
    return {h,
            hx,
            hy,
            (a.fx * a.fx + a.f * a.fxx + b.fx * b.fx + b.f * b.fxx - hx * hx) * inv,
            (a.fx * a.fy + a.f * a.fxy + b.fx * b.fy + b.f * b.fxy - hx * hy) * inv,
            (a.fy * a.fy + a.f * a.fyy + b.fy * b.fy + b.f * b.fyy - hy * hy) * inv};
  }
};

}  // namespace rb

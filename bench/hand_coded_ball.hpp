#pragma once
// Hand-coded peers for bench/perf_speed.cpp: the rolling ball of docs/model.md on
// one landscape with its derivatives written out and compiled, and RK4 and
// RKMK4 written as plain step loops, as lean as a careful engineer writes
// them for one scene: closed-form T^-1 (omega from v and N in a few
// products), the geometry (N, N', C', E) fused into one pass of scalars, no
// matrices and no temporaries in the right-hand side, built with the
// suite's own flags. They tell how much the suite's formula, its Problem
// interface and its generic tableau loops cost. For the benchmark only: the
// suite's physics lives in problems/.
#include <array>
#include <cmath>
#include <numbers>

#include "problems/so3.hpp"
#include "problems/state.hpp"

namespace rb::hand_coded {

// f, grad f and Hess f of a landscape.
struct SurfaceJet {
  double f, fx, fy, fxx, fxy, fyy;
};

// valley-sideways: cos(x*pi + pi)/10 - y/10, the same expression as the
// scene's formula (so the argument of cos rounds the same way).
struct ValleySurface {
  SurfaceJet operator()(double x, double y) const {
    constexpr double pi = std::numbers::pi;
    const double u = x * pi + pi;
    const double c = std::cos(u), s = std::sin(u);
    return {c / 10.0 - y / 10.0, -s * pi / 10.0, -0.1, -c * pi * pi / 10.0, 0.0, 0.0};
  }
};

// bumpy-long: a (x^2 + y^2) + b sin(3x) cos(2y), one sincos per argument.
struct BumpySurface {
  double a = 0.1, b = 0.02;
  SurfaceJet operator()(double x, double y) const {
    const double s3 = std::sin(3.0 * x), c3 = std::cos(3.0 * x);
    const double s2 = std::sin(2.0 * y), c2 = std::cos(2.0 * y);
    const double bsc = b * s3 * c2;
    return {a * (x * x + y * y) + bsc,
            2.0 * a * x + 3.0 * b * c3 * c2,
            2.0 * a * y - 2.0 * b * s3 * s2,
            2.0 * a - 9.0 * bsc,
            -6.0 * b * c3 * s2,
            2.0 * a - 4.0 * bsc};
  }
};

template <class Surface>
struct Ball {
  Surface surface;
  double r = 0.1, m = 1.0, g0 = 9.81;

  // omega (3) and G(z) = (v', alpha') (5) at z = (v, alpha), as in
  // RollingBall::kinematics but in plain scalars.
  void lie_rhs(const double* z, double* omega, double* dz) const {
    const SurfaceJet f = surface(z[3], z[4]);
    // N = (-fx, -fy, 1) / w and N' = (I - N N^T) n' / w
    const double w = std::sqrt(1.0 + f.fx * f.fx + f.fy * f.fy);
    const double iw = 1.0 / w;
    const double N0 = -f.fx * iw, N1 = -f.fy * iw, N2 = iw;
    const double px = -(N0 * f.fxx + N1 * f.fxy), py = -(N0 * f.fxy + N1 * f.fyy);
    const double Nx0 = (-f.fxx - N0 * px) * iw, Nx1 = (-f.fxy - N1 * px) * iw, Nx2 = -N2 * px * iw;
    const double Ny0 = (-f.fxy - N0 * py) * iw, Ny1 = (-f.fyy - N1 * py) * iw, Ny2 = -N2 * py * iw;
    // C' = phi' + r N', E = C'^T C'
    const double Cx0 = 1.0 + r * Nx0, Cx1 = r * Nx1, Cx2 = f.fx + r * Nx2;
    const double Cy0 = r * Ny0, Cy1 = 1.0 + r * Ny1, Cy2 = f.fy + r * Ny2;
    const double E00 = Cx0 * Cx0 + Cx1 * Cx1 + Cx2 * Cx2;
    const double E01 = Cx0 * Cy0 + Cx1 * Cy1 + Cx2 * Cy2;
    const double E11 = Cy0 * Cy0 + Cy1 * Cy1 + Cy2 * Cy2;
    // omega = T^-1 v
    const double s = (5.0 / 7.0) / (m * r * r);
    const double Nv = 2.5 * (N0 * z[0] + N1 * z[1] + N2 * z[2]);
    const double w0 = (z[0] + N0 * Nv) * s, w1 = (z[1] + N1 * Nv) * s, w2 = (z[2] + N2 * Nv) * s;
    // alpha' = r E^-1 C'^T (omega x N)
    const double q0 = w1 * N2 - w2 * N1, q1 = w2 * N0 - w0 * N2, q2 = w0 * N1 - w1 * N0;
    const double b0 = Cx0 * q0 + Cx1 * q1 + Cx2 * q2, b1 = Cy0 * q0 + Cy1 * q1 + Cy2 * q2;
    const double k = r / (E00 * E11 - E01 * E01);
    const double ax = (E11 * b0 - E01 * b1) * k, ay = (E00 * b1 - E01 * b0) * k;
    // v' = m r (N x g) - m r^2 (N' alpha') x (N x omega)
    const double d0 = Nx0 * ax + Ny0 * ay, d1 = Nx1 * ax + Ny1 * ay, d2 = Nx2 * ax + Ny2 * ay;
    const double n0 = -q0, n1 = -q1, n2 = -q2;  // N x omega
    const double mr = m * r, mr2 = m * r * r;
    omega[0] = w0, omega[1] = w1, omega[2] = w2;
    dz[0] = -mr * N1 * g0 - mr2 * (d1 * n2 - d2 * n1);
    dz[1] = mr * N0 * g0 - mr2 * (d2 * n0 - d0 * n2);
    dz[2] = -mr2 * (d0 * n1 - d1 * n0);
    dz[3] = ax, dz[4] = ay;
  }

  // y' = F(y) on the flat view (R row-major, v, alpha).
  void flat_rhs(const double* y, double* dy) const {
    double w[3];
    lie_rhs(y + kOffsetV, w, dy + kOffsetV);
    for (int j = 0; j < 3; ++j) {
      const double r0 = y[j], r1 = y[3 + j], r2 = y[6 + j];
      dy[j] = w[1] * r2 - w[2] * r1;
      dy[3 + j] = w[2] * r0 - w[0] * r2;
      dy[6 + j] = w[0] * r1 - w[1] * r0;
    }
  }
};

using Flat = std::array<double, kFlatSize>;

// n classical RK4 steps of size h on the flat view.
template <class Surface>
Flat rk4(const Ball<Surface>& p, Flat y, double h, long n) {
  Flat k1, k2, k3, k4, Y;
  for (long step = 0; step < n; ++step) {
    p.flat_rhs(y.data(), k1.data());
    for (int i = 0; i < kFlatSize; ++i) Y[i] = y[i] + 0.5 * h * k1[i];
    p.flat_rhs(Y.data(), k2.data());
    for (int i = 0; i < kFlatSize; ++i) Y[i] = y[i] + 0.5 * h * k2[i];
    p.flat_rhs(Y.data(), k3.data());
    for (int i = 0; i < kFlatSize; ++i) Y[i] = y[i] + h * k3[i];
    p.flat_rhs(Y.data(), k4.data());
    for (int i = 0; i < kFlatSize; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  }
  return y;
}

// n RKMK4 steps (RK4 tableau, closed-form dexpinv) of size h.
template <class Surface>
Flat rkmk4(const Ball<Surface>& p, Flat y, double h, long n) {
  using Z = std::array<double, kZSize>;
  for (long step = 0; step < n; ++step) {
    Z z, Zs;
    for (int i = 0; i < kZSize; ++i) z[i] = y[kOffsetV + i];
    std::array<Vec3, 4> K;
    std::array<Z, 4> L;
    constexpr double a[4] = {0.0, 0.5, 0.5, 1.0};
    for (int s = 0; s < 4; ++s) {
      for (int i = 0; i < kZSize; ++i) Zs[i] = s == 0 ? z[i] : z[i] + a[s] * h * L[s - 1][i];
      Vec3 omega;
      p.lie_rhs(Zs.data(), omega.data(), L[s].data());
      K[s] = s == 0 ? omega : dexpinv(Vec3(a[s] * h * K[s - 1]), omega);
    }
    const Vec3 u = h / 6.0 * (K[0] + 2.0 * (K[1] + K[2]) + K[3]);
    const Mat3 R = so3_exp(u) * Eigen::Map<const RowMajorMat3>(y.data());
    Eigen::Map<RowMajorMat3>(y.data()) = R;
    for (int i = 0; i < kZSize; ++i) y[kOffsetV + i] = z[i] + h / 6.0 * (L[0][i] + 2.0 * (L[1][i] + L[2][i]) + L[3][i]);
  }
  return y;
}

}  // namespace rb::hand_coded

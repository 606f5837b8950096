#pragma once
// One Runge-Kutta-Munthe-Kaas step (docs/model.md, "The methods compared"), shared by RKMK with
// the exponential and with the Cayley map (munthe_kaas.cpp): the coordinate
// map is a parameter.
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "integrators/driver.hpp"
#include "integrators/run_book.hpp"
#include "integrators/stage_terms.hpp"
#include "problems/cayley.hpp"
#include "problems/so3.hpp"

namespace rb {

// The rotation a homogeneous ball's Lie-view right-hand side is given: it
// does not read it (RollingBall::lie_rhs).
inline const Mat3 kAnyRotation = Mat3::Identity();

// exp by Rodrigues' formula and its dexpinv (closed form, series or the
// seminar's). Inlined into the stage loop: out of line, each dexpinv passed
// its vectors through memory (callgrind: 76 instructions a call).
struct ExpCoordinates {
  DexpinvKind kind;
  // Called where a stage's dexpinv is not finite: past the chart's edge
  // (|u| >= kDexpinvMaxAngle, the closed form's pole) the step cannot be
  // taken in these coordinates, which is the status chart-limit, not a
  // divergence of the state.
  void check_chart(const Vec3& u) const {
    // a NaN stage (the state itself not finite) is no chart's edge
    if (kind == DexpinvKind::exact && u.norm() >= kDexpinvMaxAngle) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "a stage turns the ball by |u| = %.4g rad, past the exponential chart's edge (%.4g rad, "
                    "dexpinv's pole at 2 pi): the step is too large for these coordinates",
                    u.norm(), kDexpinvMaxAngle);
      throw StepFailure(Status::chart_limit, text);
    }
  }
  [[gnu::always_inline]] Mat3 exp(const Vec3& u) const { return so3_exp(u); }
  [[gnu::always_inline]] Vec3 dexpinv(const Vec3& u, const Vec3& w) const { return rb::dexpinv(u, w, kind); }
};

// The Cayley map and its dcayinv, counted as exp and dexpinv.
struct CayleyCoordinates {
  [[gnu::always_inline]] Mat3 exp(const Vec3& u) const { return so3_cay(u); }
  [[gnu::always_inline]] Vec3 dexpinv(const Vec3& u, const Vec3& w) const { return dcayinv(u, w); }
  void check_chart(const Vec3& /*u*/) const {}  // dcayinv has no pole
};

// One step with S stages (S = 0: any number), so that the stage loop unrolls
// around the inlined right-hand side, as in runge_kutta.cpp.
template <int S, class Coordinates>
struct MkStep {
  // Run only by drive_fixed_step (stepped_method), which never reads
  // Cost::watch.near: the stages skip that test (Cost::note).
  static constexpr bool kWatchNear = false;
  const Problem& problem;
  const StageTerms& terms;
  Coordinates map;                    // exp and dexpinv, or cay and dcayinv
  bool anisotropic;                   // stage orientations needed
  std::array<Vec3, kMaxStages>& K;    // u' at the stages
  std::array<ZState, kMaxStages>& L;  // z' at the stages

  // every stage's validity margins are noted in cost (stage_lie_rhs)
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) const {
    const int stages = S > 0 ? S : terms.stages;
    const ZState z = z_of(y);
    // R_n, read in place: the homogeneous ball's right-hand side does not
    // read R, so its stages are given any rotation and R_n is read once, by
    // the update; only an anisotropic ball's stages take a copy
    const Eigen::Map<const RowMajorMat3> Rn(y.data() + kOffsetR);
    Mat3 R_copy;
    const Mat3* R = &kAnyRotation;
    if (anisotropic) {
      R_copy = Rn;
      R = &R_copy;
    }
    // the first stage, at u = 0 (dexpinv the identity) and R itself
    stage_lie_rhs<kWatchNear>(problem, *R, z.data(), K[0].data(), L[0].data(), cost);
    const auto stage = [&](std::size_t i) __attribute__((always_inline)) {
      const StageTerms::Row& row = terms.a[i];
      // U = sum h a_ij K_j, Z = z + sum h a_ij L_j over the non-zero terms
      ZState Z;
      Vec3 U;
      row.sum(Z, z, h, L);
      row.sum(U, h, K);
      Vec3 omega;
      if (anisotropic) {
        // R enters omega and G: evaluate at the stage's own orientation
        stage_lie_rhs<kWatchNear>(problem, Mat3(map.exp(U) * *R), Z.data(), omega.data(), L[i].data(), cost);
        ++cost.exp_evals;
      } else {
        stage_lie_rhs<kWatchNear>(problem, *R, Z.data(), omega.data(), L[i].data(), cost);
      }
      K[i] = map.dexpinv(U, omega);
      ++cost.dexpinv_evals;
      if (!std::isfinite(K[i].x())) [[unlikely]]
        map.check_chart(U);
    };
    // a known stage count unrolled in full (as a loop, GCC kept rkmk4's
    // three later stages one loop body, callgrind: 487 instructions run 3 times)
    if constexpr (S > 0) {
      [&]<std::size_t... I>(std::index_sequence<I...>) __attribute__((always_inline)) { (stage(I + 1), ...); }
      (std::make_index_sequence<S - 1>{});
    } else {
      for (std::size_t i = 1; i < static_cast<std::size_t>(stages); ++i) stage(i);
    }
    Vec3 u;
    ZState dz;
    terms.b.sum(u, h, K);
    terms.b.sum(dz, h, L);
    Eigen::Map<RowMajorMat3>(next.data() + kOffsetR).noalias() = map.exp(u) * Rn;
    next.tail<kZSize>() = z + dz;
    cost.rhs_evals += stages;
    ++cost.exp_evals;
  }
};

}  // namespace rb

#include "integrators/munthe_kaas.hpp"

#include <array>

#include "integrators/fixed_step.hpp"

namespace rb {

MuntheKaas::MuntheKaas(Tableau tableau, std::string name, DexpinvKind dexpinv)
    : tableau_(std::move(tableau)), name_(std::move(name)), dexpinv_(dexpinv) {}

std::string MuntheKaas::description() const {
  const char* kind = dexpinv_ == DexpinvKind::exact       ? "closed-form dexpinv"
                     : dexpinv_ == DexpinvKind::truncated ? "dexpinv series to u x (u x w) / 12"
                                                          : "the seminar's dexpinv with its sign error";
  return "Runge-Kutta-Munthe-Kaas (" + tableau_.name() + " tableau, " + kind + ") on the Lie-group view";
}

RunResult MuntheKaas::integrate(const Problem& problem, const RunOptions& options) const {
  const Tableau& tab = tableau_;
  const int s = tab.stages();
  std::array<Vec3, kMaxStages> K;    // u' at the stages
  std::array<ZState, kMaxStages> L;  // z' at the stages
  auto step = [&](FlatState& y, double /*t*/, double h, Cost& cost) {
    const ZState z = z_of(y);
    for (int i = 0; i < s; ++i) {
      Vec3 U = Vec3::Zero();
      ZState Z = z;
      bool moved = false;
      for (int j = 0; j < i; ++j) {
        const double ha = h * tab.a(i, j);
        if (ha == 0.0) continue;
        U += ha * K[j];
        Z += ha * L[j];
        moved = true;
      }
      Vec3 omega;
      problem.lie_rhs(Z.data(), omega.data(), L[i].data());
      // at u = 0, dexpinv is the identity
      if (moved) {
        K[i] = dexpinv(U, omega, dexpinv_);
        ++cost.dexpinv_evals;
      } else {
        K[i] = omega;
      }
    }
    Vec3 u = Vec3::Zero();
    ZState dz = ZState::Zero();
    for (int i = 0; i < s; ++i) {
      if (tab.b(i) == 0.0) continue;
      u += (h * tab.b(i)) * K[i];
      dz += (h * tab.b(i)) * L[i];
    }
    set_rotation(y, so3_exp(u) * rotation_of(y));
    y.tail<kZSize>() = z + dz;
    cost.rhs_evals += s;
    ++cost.exp_evals;
  };
  return drive_fixed_step(problem, options, step);
}

}  // namespace rb

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

namespace {

// One step with S stages (S = 0: any number), so that the stage loop unrolls
// around the inlined right-hand side, as in runge_kutta.cpp.
template <int S>
struct MkStep {
  const Problem& problem;
  const StageTerms& terms;
  DexpinvKind kind;
  std::array<Vec3, kMaxStages>& K;    // u' at the stages
  std::array<ZState, kMaxStages>& L;  // z' at the stages

  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost) const {
    const int stages = S > 0 ? S : terms.stages;
    const ZState z = z_of(y);
    for (std::size_t i = 0; i < static_cast<std::size_t>(stages); ++i) {
      const StageTerms::Row& row = terms.a[i];
      Vec3 omega;
      if (row.count == 0) {
        // at u = 0, dexpinv is the identity
        problem.lie_rhs(z.data(), omega.data(), L[i].data());
        K[i] = omega;
        continue;
      }
      // U = sum h a_ij K_j, Z = z + sum h a_ij L_j over the non-zero terms
      ZState Z;
      Vec3 U;
      row.sum(Z, z, h, L);
      row.sum(U, h, K);
      problem.lie_rhs(Z.data(), omega.data(), L[i].data());
      K[i] = dexpinv(U, omega, kind);
      ++cost.dexpinv_evals;
    }
    Vec3 u;
    ZState dz;
    terms.b.sum(u, h, K);
    terms.b.sum(dz, h, L);
    set_rotation(next, so3_exp(u) * rotation_of(y));
    next.tail<kZSize>() = z + dz;
    cost.rhs_evals += stages;
    ++cost.exp_evals;
  }
};

}  // namespace

RunResult MuntheKaas::integrate(const Problem& problem, const RunOptions& options) const {
  const StageTerms terms(tableau_);
  std::array<Vec3, kMaxStages> K;
  std::array<ZState, kMaxStages> L;
  switch (terms.stages) {
    case 1: return drive_fixed_step(problem, options, MkStep<1>{problem, terms, dexpinv_, K, L});
    case 2: return drive_fixed_step(problem, options, MkStep<2>{problem, terms, dexpinv_, K, L});
    case 3: return drive_fixed_step(problem, options, MkStep<3>{problem, terms, dexpinv_, K, L});
    case 4: return drive_fixed_step(problem, options, MkStep<4>{problem, terms, dexpinv_, K, L});
    default: return drive_fixed_step(problem, options, MkStep<0>{problem, terms, dexpinv_, K, L});
  }
}

}  // namespace rb

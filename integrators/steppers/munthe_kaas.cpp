#include "integrators/steppers/munthe_kaas.hpp"

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
  bool anisotropic;                   // stage orientations needed
  std::array<Vec3, kMaxStages>& K;    // u' at the stages
  std::array<ZState, kMaxStages>& L;  // z' at the stages

  // margins: the validity margins at y, from the first stage (at y itself)
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost,
                  ModelMargins& margins) const {
    const int stages = S > 0 ? S : terms.stages;
    const ZState z = z_of(y);
    const Mat3 R = rotation_of(y);
    // the first stage, at u = 0 (dexpinv the identity) and R itself
    problem.lie_rhs(R, z.data(), K[0].data(), L[0].data(), margins);
    for (std::size_t i = 1; i < static_cast<std::size_t>(stages); ++i) {
      const StageTerms::Row& row = terms.a[i];
      // U = sum h a_ij K_j, Z = z + sum h a_ij L_j over the non-zero terms
      ZState Z;
      Vec3 U;
      row.sum(Z, z, h, L);
      row.sum(U, h, K);
      Vec3 omega;
      if (anisotropic) {
        // R enters omega and G: evaluate at the stage's own orientation
        problem.lie_rhs(Mat3(so3_exp(U) * R), Z.data(), omega.data(), L[i].data());
        ++cost.exp_evals;
      } else {
        problem.lie_rhs(R, Z.data(), omega.data(), L[i].data());
      }
      K[i] = dexpinv(U, omega, kind);
      ++cost.dexpinv_evals;
    }
    Vec3 u;
    ZState dz;
    terms.b.sum(u, h, K);
    terms.b.sum(dz, h, L);
    set_rotation(next, so3_exp(u) * R);
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
  const bool aniso = problem.model().anisotropic();
  switch (terms.stages) {
    case 1: return drive_fixed_step(problem, options, MkStep<1>{problem, terms, dexpinv_, aniso, K, L});
    case 2: return drive_fixed_step(problem, options, MkStep<2>{problem, terms, dexpinv_, aniso, K, L});
    case 3: return drive_fixed_step(problem, options, MkStep<3>{problem, terms, dexpinv_, aniso, K, L});
    case 4: return drive_fixed_step(problem, options, MkStep<4>{problem, terms, dexpinv_, aniso, K, L});
    default: return drive_fixed_step(problem, options, MkStep<0>{problem, terms, dexpinv_, aniso, K, L});
  }
}

}  // namespace rb

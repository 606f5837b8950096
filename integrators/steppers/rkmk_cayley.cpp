#include "integrators/steppers/rkmk_cayley.hpp"

#include <array>

#include "integrators/cayley.hpp"
#include "integrators/fixed_step.hpp"

namespace rb {

MuntheKaasCayley::MuntheKaasCayley(Tableau tableau, std::string name)
    : tableau_(std::move(tableau)), name_(std::move(name)) {}

std::string MuntheKaasCayley::description() const {
  return "Runge-Kutta-Munthe-Kaas (" + tableau_.name() +
         " tableau) with the Cayley map for coordinates; cayley maps counted as exp, dcayinv as dexpinv";
}

namespace {

// One step, in the shape of munthe_kaas.cpp's with cay and dcayinv for exp
// and dexpinv.
struct CayleyStep {
  const Problem& problem;
  const StageTerms& terms;
  bool anisotropic;                   // stage orientations needed
  std::array<Vec3, kMaxStages>& K;    // u' at the stages
  std::array<ZState, kMaxStages>& L;  // z' at the stages

  // margins: the validity margins at y, from the first stage (at y itself)
  void operator()(const FlatState& y, FlatState& next, double /*t*/, double h, Cost& cost,
                  ModelMargins& margins) const {
    const ZState z = z_of(y);
    const Mat3 R = rotation_of(y);
    // the first stage, at u = 0 (dcayinv the identity) and R itself
    problem.lie_rhs(R, z.data(), K[0].data(), L[0].data(), margins);
    for (std::size_t i = 1; i < static_cast<std::size_t>(terms.stages); ++i) {
      ZState Z;
      Vec3 U;
      terms.a[i].sum(Z, z, h, L);
      terms.a[i].sum(U, h, K);
      Vec3 omega;
      if (anisotropic) {
        problem.lie_rhs(Mat3(so3_cay(U) * R), Z.data(), omega.data(), L[i].data());
        ++cost.exp_evals;
      } else {
        problem.lie_rhs(R, Z.data(), omega.data(), L[i].data());
      }
      K[i] = dcayinv(U, omega);
      ++cost.dexpinv_evals;
    }
    Vec3 u;
    ZState dz;
    terms.b.sum(u, h, K);
    terms.b.sum(dz, h, L);
    set_rotation(next, so3_cay(u) * R);
    next.tail<kZSize>() = z + dz;
    cost.rhs_evals += terms.stages;
    ++cost.exp_evals;
  }
};

}  // namespace

RunResult MuntheKaasCayley::integrate(const Problem& problem, const RunOptions& options) const {
  const StageTerms terms(tableau_);
  std::array<Vec3, kMaxStages> K;
  std::array<ZState, kMaxStages> L;
  return drive_fixed_step(problem, options, CayleyStep{problem, terms, problem.model().anisotropic(), K, L});
}

}  // namespace rb

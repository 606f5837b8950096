#pragma once
// Lie-group methods that need only exponentials (docs/model.md, "The methods compared"): the
// commutator-free methods and, as their special case with one field per
// exponential, the Crouch-Grossman methods. Over a step, F_j = (omega_j,
// G_j) is the vector field at stage j, frozen: it moves R by
// R -> exp(h hat(omega_j)) R and z by z -> z + h G_j. A stage's orientation,
// and R_{n+1}, is a product of exponentials of sums of frozen fields applied
// to R_n; on SO(3) x R^5 the z part of such a product is a plain sum, so only
// the order of the SO(3) factors matters.
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

// sum_j coeff[j] F_j over the stages j (trailing zeros may be left out)
using FieldSum = std::vector<double>;

// The exponentials of one product, in the order they are applied: the first
// acts on R_n first, R -> exp(h hat(sum_j c_j omega_j)) R.
using ExpProduct = std::vector<FieldSum>;

struct ExpProductScheme {
  std::string name;                // registry name, e.g. "cf4"
  std::string family;              // "cf" or "cg"
  std::string kind;                // the family in words, for the description
  int order = 0;                   // as the paper states it
  int rotation_order = 0;          // where the composition loses order in R; 0: order
  std::vector<ExpProduct> stages;  // stage i's product (stage 0: empty, R_n itself)
  ExpProduct update;               // R_{n+1}
  ExpProduct embedded;             // a lower-order R_{n+1} for an error estimate (empty: none)
  int embedded_order = 0;          // its order (0: none)
  std::string source;              // where the coefficients are from
};

// The same factors with every product (stages and update) composed in the
// opposite order (the embedded update too), under the name given: what an implementation that reads
// the paper's products the other way round computes. Its order stays the
// paper's (what a user of it expects); its rotation_order is 2: the h^3
// commutator term of the update changes sign (crouch_grossman.cpp), and
// ordering enters no condition below it.
ExpProductScheme reversed(ExpProductScheme scheme, std::string name);

class ExpProductMethod final : public Integrator {
 public:
  // Throws std::invalid_argument for a scheme whose stage uses a field not
  // yet computed.
  explicit ExpProductMethod(ExpProductScheme scheme);
  RunResult integrate(const Problem& problem, const RunOptions& options) const override;

  const ExpProductScheme& scheme() const { return scheme_; }
  // so(3) exponentials a step computes: with stage orientations (an
  // anisotropic ball) or only the update's (a homogeneous ball, where R
  // enters neither omega nor G)
  int exponentials_per_step(bool anisotropic) const;

 private:
  ExpProductScheme scheme_;
};

}  // namespace rb

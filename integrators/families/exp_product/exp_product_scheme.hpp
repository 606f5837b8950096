#pragma once
// The method data of a Lie-group method that needs only exponentials
// (docs/model.md, "The methods compared"): the commutator-free methods and,
// as their special case with one field per exponential, the Crouch-Grossman
// methods, as Tableau is a Runge-Kutta method's. Over a step, F_j =
// (omega_j, G_j) is the vector field at stage j, frozen: it moves R by
// R -> exp(h hat(omega_j)) R and z by z -> z + h G_j. A stage's orientation,
// and R_{n+1}, is a product of exponentials of sums of frozen fields applied
// to R_n; on SO(3) x R^5 the z part of such a product is a plain sum, so only
// the order of the SO(3) factors matters. The schemes themselves are files
// beside this one (cf4.hpp, cg3.hpp, cg4a.hpp, ...); their stepper is
// exp_product_stepper.hpp, their integrators exp_product.hpp.
#include <string>
#include <vector>

namespace rb {

// sum_j coeff[j] F_j over the stages j (trailing zeros may be left out)
using FieldSum = std::vector<double>;

// The exponentials of one product, in the order they are applied: the first
// acts on R_n first, R -> exp(h hat(sum_j c_j omega_j)) R.
using ExpProduct = std::vector<FieldSum>;

struct ExpProductScheme {
  std::string name;                // the scheme's name, e.g. "cf4" (a registry line names the method)
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
// opposite order (the embedded update too): what an implementation that
// reads the paper's products the other way round computes. Its order stays
// the paper's (what a user of it expects); its rotation_order is 2: the h^3
// commutator term of the update changes sign (methods/cg3.hpp), and
// ordering enters no condition below it. name: the scheme's new name
// (empty: the old one with "-reversed").
ExpProductScheme reversed(ExpProductScheme scheme, std::string name = {});

// exp(w_s F_s) ... exp(w_1 F_1): one field per exponential, F_1 first (the
// Crouch-Grossman shape of a product).
ExpProduct one_field_each(const std::vector<double>& w);

// A Crouch-Grossman scheme (family "cg") from its a (row i: stage i + 2's
// weights) and b: stage i's orientation is exp(a_{i,i-1} F_{i-1}) ...
// exp(a_{i,1} F_1) R_n and R_{n+1} = exp(b_s F_s) ... exp(b_1 F_1) R_n.
ExpProductScheme crouch_grossman(std::string name, int order, const std::vector<std::vector<double>>& a,
                                 const std::vector<double>& b, std::string source);

}  // namespace rb

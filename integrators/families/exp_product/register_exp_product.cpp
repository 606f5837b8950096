// Commutator-free and Crouch-Grossman methods: products of exponentials only
// (exp_product.hpp). The -reversed variants compose every product the other
// way round (order 2 in R, and where R feeds back in every component).
#include "integrators/controllers/controller.hpp"
#include "integrators/families/exp_product/cf3.hpp"
#include "integrators/families/exp_product/cf4.hpp"
#include "integrators/families/exp_product/cg3.hpp"
#include "integrators/families/exp_product/cg4a.hpp"
#include "integrators/families/exp_product/cg5a.hpp"
#include "integrators/families/exp_product/exp_product.hpp"
#include "integrators/families/families.hpp"

namespace rb {

void register_exp_product(MethodList& list) {
  namespace m = methods;
  const std::string constant = kConstantController, pi = "pi";
  list.push_back(exp_product_method(m::cf3(), "cf3", constant));
  list.push_back(exp_product_method(m::cf4(), "cf4", constant));
  list.push_back(exp_product_method(m::cg3(), "cg3", constant));
  list.push_back(exp_product_method(m::cg4a(), "cg4a", constant));
  list.push_back(exp_product_method(m::cg5a(), "cg5a", constant));
  list.push_back(exp_product_method(reversed(m::cf4()), "cf4-reversed", constant));
  list.push_back(exp_product_method(reversed(m::cg3()), "cg3-reversed", constant));
  list.push_back(exp_product_method(reversed(m::cg4a()), "cg4a-reversed", constant));
  list.push_back(exp_product_method(m::cg3_pair(), "cg3-adaptive", pi));
  list.push_back(exp_product_method(m::cf4_pair(), "cf4-adaptive", pi));
}

}  // namespace rb

#include "integrators/families/exp_product/exp_product_scheme.hpp"

#include <algorithm>
#include <utility>

namespace rb {

ExpProductScheme reversed(ExpProductScheme scheme, std::string name) {
  for (ExpProduct& product : scheme.stages) std::reverse(product.begin(), product.end());
  std::reverse(scheme.update.begin(), scheme.update.end());
  std::reverse(scheme.embedded.begin(), scheme.embedded.end());
  scheme.name = name.empty() ? scheme.name + "-reversed" : std::move(name);
  scheme.rotation_order = std::min(scheme.order, 2);
  scheme.source += ", every product composed in the opposite order";
  return scheme;
}

ExpProduct one_field_each(const std::vector<double>& w) {
  ExpProduct p;
  for (std::size_t j = 0; j < w.size(); ++j) {
    FieldSum f(j + 1, 0.0);
    f[j] = w[j];
    p.push_back(f);
  }
  return p;
}

ExpProductScheme crouch_grossman(std::string name, int order, const std::vector<std::vector<double>>& a,
                                 const std::vector<double>& b, std::string source) {
  ExpProductScheme s;
  s.name = std::move(name);
  s.family = "cg";
  s.kind = "Crouch-Grossman";
  s.order = order;
  s.stages.push_back({});
  for (const auto& row : a) s.stages.push_back(one_field_each(row));
  s.update = one_field_each(b);
  s.source = std::move(source);
  return s;
}

}  // namespace rb

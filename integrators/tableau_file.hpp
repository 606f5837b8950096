#pragma once
// A Butcher tableau from a JSON file (docs/formats.md, "Butcher tableau"): name,
// order (optional), c, A, b or the seminar's `butcher` matrix, an optional
// embedded b_err with err_order, and a source. Everything is checked on
// loading: the shape (square, explicit), finiteness, rows summing to c, and
// every order condition up to the declared orders.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/tableau.hpp"

namespace rb {

struct TableauFile {
  std::string path;  // as given
  Tableau tableau;   // named after the file's name; its order is the declared one, or the highest that holds
  bool order_declared = false;
  // b_err and err_order are the tableau's e() = b - b_err and
  // embedded_order(), the source its source()
};

// Loads and checks the tableau file at path. Throws InputError whose message
// names the file, then the key and what is wrong, e.g.
// "tableau file 'x.json': 'A': row 1 has 2 entries, not 3 (A must be square)";
// for a failed order condition also the tree, its order and the residual.
TableauFile load_tableau_file(const std::string& path);

// The same for a file's text; path only names it in errors.
TableauFile parse_tableau_file(std::string_view text, const std::string& path);

}  // namespace rb

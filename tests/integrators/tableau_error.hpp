#pragma once
// The error a tableau file's text gets on loading, as the user reads it, for
// tests that compare messages; "no error" when it loads.
#include <string>

#include "integrators/tableau_file.hpp"
#include "problems/input_error.hpp"

namespace rb::testing {

inline std::string tableau_error_of(const std::string& text) {
  try {
    parse_tableau_file(text, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace rb::testing

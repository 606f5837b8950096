#pragma once
// Tests parametrised over registry names: GoogleTest allows only letters,
// digits and '_' in a test's name, so "odeint-rk4" becomes "odeint_rk4".
#include <gtest/gtest.h>

#include <cctype>
#include <string>

namespace rb::testing {

inline std::string registry_test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

}  // namespace rb::testing

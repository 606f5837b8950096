#pragma once
// The registry-wide order test's scene where R feeds back
// (tests/data/chaplygin-bowl-order.json; why this scene: test_registry_order.cpp).
#include <string>

#include "problems/problem.hpp"
#include "problems/scene.hpp"

namespace rb::testing {

inline const Problem& chaplygin_bowl() {
  static const Problem problem = make_problem(load_scene(std::string(RB_TEST_DATA) + "/chaplygin-bowl-order.json"));
  return problem;
}

}  // namespace rb::testing

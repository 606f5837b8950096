#pragma once
// The registry-wide order test's scene where R feeds back
// (problems/scenes/chaplygin-bowl.json; why this scene: test_registry_order.cpp).
#include <string>

#include "problems/problem.hpp"
#include "problems/scene.hpp"

namespace rb::testing {

inline const Problem& chaplygin_bowl() {
  static const Problem problem = make_problem(load_scene("chaplygin-bowl"));
  return problem;
}

}  // namespace rb::testing

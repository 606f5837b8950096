#pragma once
// What the robustness suites share: a small valid scene to break, the CLI as
// a user runs it, and one method per family and driver from the registry
// (never a list of names, so a new family is covered the day it registers).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench/lib/trajectory_csv.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/cli_run.hpp"

namespace rb::robustness {

// A valid scene as JSON text; tests replace one piece of it.
inline std::string base_scene_text() {
  return R"({"name": "base", "landscape": "a*x^2 - y/10", "params": {"a": 0.5},
    "domain": [-2, 2, -2, 2], "ball": {"radius": 0.1, "mass": 1.0}, "gravity": 9.81,
    "start": {"contact": [0.0, 0.0], "velocity": [0.5, 0.0, 0.0], "spin": 0.0, "orientation": [1, 0, 0, 0]},
    "t_end": 1.0})";
}

// text with its first occurrence of from replaced by to (which must exist).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The InputError parse_scene throws for text (or a failure when none).
inline InputError scene_error(const std::string& text) {
  try {
    parse_scene(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for: " << text;
  return InputError("<no error>");
}

inline Problem data_problem(const std::string& file) {
  return make_problem(load_scene(std::string(RB_TEST_DATA) + "/" + file));
}

using testing::CliOutcome;
using testing::slurp;

// A file name of this process in the temp directory.
inline std::filesystem::path temp_path(const std::string& name) { return testing::cli_temp_file(name); }

// rollbench args, with its exit code, stdout and stderr.
inline CliOutcome rollbench(const std::string& args) { return testing::run_rollbench(args); }

// The first registered method of each (family, fixed | adaptive) pair:
// every family and driver that exists, each once.
inline std::vector<const Integrator*> one_per_family_and_driver() {
  std::map<std::pair<std::string, bool>, const Integrator*> first;
  std::vector<const Integrator*> out;
  for (const auto& m : registry())
    if (first.emplace(std::make_pair(m->family(), m->adaptive()), m.get()).second) out.push_back(m.get());
  return out;
}

// Options a method takes: a fixed step h, or rtol = atol = tol; outputs every dt.
inline RunOptions options_for(const Integrator& m, double t_end, double h, double tol, double dt) {
  RunOptions o;
  o.t_end = t_end;
  if (m.adaptive()) {
    o.tolerances = Tolerances(tol, tol);
  } else {
    o.h = h;
  }
  o.output_times = equally_spaced_outputs(dt, t_end);
  return o;
}

}  // namespace rb::robustness

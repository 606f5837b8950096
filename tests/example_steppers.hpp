#pragma once
// The example plug-in libraries that examples/ builds (libNAME.so in the
// build's examples folder), for the plug-in tests.
#include <string>

namespace rb::testing {

inline std::string example_stepper_dir() { return RB_STEPPER_DIR; }

inline std::string example_stepper(const std::string& name) { return example_stepper_dir() + "/lib" + name + ".so"; }

}  // namespace rb::testing

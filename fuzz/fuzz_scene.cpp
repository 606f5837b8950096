// libFuzzer target: any bytes as a scene file. parse_scene may only throw
// InputError; a scene it accepts must become a problem whose start is finite
// and passes the full validity check (parse_scene promises a regular start).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "problems/input_error.hpp"
#include "problems/scene.hpp"

namespace {

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_scene: %s: %s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

// a compiler run per new landscape would stall the fuzzer: the tape it is
// (fuzz_formula compares the native code with the tape)
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("RB_NATIVE_FORMULA", "off", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rb::Scene scene;
  try {
    scene = rb::parse_scene(text, "<fuzz>");
  } catch (const rb::InputError& e) {
    if (e.message().empty()) fail("an InputError without a message", e.what());
    return 0;
  }
  // accepted: building the problem must not throw, and its start is valid
  const rb::Problem problem = rb::make_problem(scene);
  if (!problem.y0().allFinite()) fail("an accepted scene starts non-finite", scene.name);
  // a normal t_end in its bounds (a subnormal one underflowed fuzz_run's step)
  if (!(problem.t_end() >= rb::kMinTEnd && problem.t_end() <= rb::kMaxTEnd))
    fail("an accepted scene has a t_end out of its bounds", scene.name);
  const rb::Validity v = problem.check_step(problem.y0());
  if (v.status != rb::Status::ok) fail("an accepted scene starts outside its domain or non-finite", v.reason);
  // the full check may say curvature or lift-off (gravity 0 gives F.N = 0 on
  // a plane); it must not crash, and must give a reason when not ok
  const rb::Validity full = problem.check_full(problem.y0());
  if (full.status != rb::Status::ok && full.reason.empty()) fail("a stop without a reason", scene.name);
  return 0;
}

// libFuzzer target: any text as a landscape formula. Formula::parse may
// only throw InputError (with a column inside the text, or one past it);
// an accepted formula is evaluated (value, gradient and Hessian, in doubles
// and on the integrators' AD type) at a few points derived from the input,
// which must never crash, and must agree where the header promises it.
//
// Native code (formula_native.hpp) costs a compiler run, far too slow for
// every input: each input's C source is generated in-process (so the code
// generator sees every tape), and the first kNativeCap formulas of a run
// whose source is new are compiled and must give the tape's bits at the
// same points. The corpus itself is compiled in full by
// tests/problems/test_formula_native.cpp.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <unsupported/Eigen/AutoDiff>

#include "problems/formula.hpp"
#include "problems/formula_codegen.hpp"
#include "problems/native_cache.hpp"

namespace rb {
namespace {

using AD2 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2, 1>>;

// a fuzz finding: print why and abort, so libFuzzer saves the input
[[noreturn]] void fail(const char* what, const std::string& text) {
  std::fprintf(stderr, "fuzz_formula: %s\nformula: %s\n", what, text.c_str());
  std::abort();
}

// the same double, or both NaN
bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

// relative agreement for results computed along different code paths
bool close(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return true;
  return std::abs(a - b) <= 1e-9 * (1.0 + std::abs(a) + std::abs(b));
}

// FNV-1a: points that differ from input to input without reading past it
std::uint64_t hash_of(const std::uint8_t* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
  return h;
}

double coordinate(std::uint64_t bits) {
  // in [-4, 4]: where landscapes live
  return -4.0 + 8.0 * static_cast<double>(bits >> 11) / 9007199254740992.0;
}

void check_point(const Formula& f, double x, double y, const std::string& text) {
  const double v = f.value(x, y);
  const Jet2<double> j = f.eval(x, y);
  // formula.hpp: value() is bitwise equal to eval(x, y).f for double
  if (!same(v, j.f)) fail("value() differs from eval().f", text);
  // the stack machine on an AD type against the tape (parts that are
  // structurally zero may be 0 on the tape and NaN on the stack)
  const Jet2<AD2> a = f.eval(AD2(x, 2, 0), AD2(y, 2, 1));
  if (!close(a.f.value(), j.f) || !close(a.fx.value(), j.fx) || !close(a.fy.value(), j.fy) ||
      !close(a.fxx.value(), j.fxx) || !close(a.fxy.value(), j.fxy) || !close(a.fyy.value(), j.fyy))
    fail("eval on AD numbers differs from eval on doubles", text);
}

constexpr std::size_t kNativeCap = 8;

// the tape's jets against native code's, bit for bit (NaN as NaN)
void check_native(const Formula& tape, const Formula& native, double x, double y, const std::string& text) {
  const Jet2<double> a = tape.eval(x, y), b = native.eval(x, y);
  const Jet2<double> sa = tape.slopes(x, y), sb = native.slopes(x, y);
  const double pa[12] = {a.f, a.fx, a.fy, a.fxx, a.fxy, a.fyy, sa.f, sa.fx, sa.fy, sa.fxx, sa.fxy, sa.fyy};
  const double pb[12] = {b.f, b.fx, b.fy, b.fxx, b.fxy, b.fyy, sb.f, sb.fx, sb.fy, sb.fxx, sb.fxy, sb.fyy};
  for (int i = 0; i < 12; ++i)
    if (!(std::isnan(pa[i]) && std::isnan(pb[i])) && std::memcmp(&pa[i], &pb[i], sizeof(double)) != 0)
      fail("native code differs from the tape", text);
}

// a fresh cache folder per fuzzer process, so each compiled input is built:
// the private mkdtemp folder (removed when the fuzzer exits)
NativeSettings fuzz_native_settings() {
  NativeSettings s;
  s.cache_dir = default_cache_folder(nullptr, nullptr);
  return s;
}

}  // namespace
}  // namespace rb

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rb;
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const std::map<std::string, double> params = {{"a", 0.5}, {"b", -2.0}, {"big", 1e300}};
  Formula f;
  try {
    f = Formula::parse(text, params);
  } catch (const InputError& e) {
    if (e.column() < 0 || static_cast<std::size_t>(e.column()) > text.size() + 1)
      fail("an error's column lies outside the text", text);
    if (e.message().empty()) fail("an error without a message", text);
    return 0;
  }
  if (f.stack_depth() > Formula::kMaxStack) fail("stack deeper than kMaxStack", text);
  const std::uint64_t h = hash_of(data, size);
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double points[][2] = {
      {0.0, 0.0},
      {0.3, -0.7},
      {coordinate(h), coordinate(h * 0x9E3779B97F4A7C15ull)},
      {-1e300, 1e-300},
      {inf, std::numeric_limits<double>::quiet_NaN()},
  };
  for (const auto& p : points) check_point(f, p[0], p[1], text);

  if (!f.tape().usable()) return 0;
  static std::set<std::string> seen;
  const std::string source = formula_c_source(f.tape());
  if (seen.size() >= kNativeCap || !seen.insert(source).second) return 0;
  static const NativeSettings settings = fuzz_native_settings();
  Formula native = f;
  if (native.compile_native(settings) != NativeOutcome::built) fail("native code could not be built", text);
  for (const auto& p : points) check_native(f, native, p[0], p[1], text);
  return 0;
}

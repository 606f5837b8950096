#pragma once
// A formula's tape compiled to machine code at run time: the tape as C
// (formula_codegen.hpp), built by the system's C compiler into a shared
// object, cached on disk and loaded with dlopen (formula_native.cpp).
//
// Settings, read from the environment once per process:
//   RB_NATIVE_FORMULA=off   keep the tape (tests and fuzzers use it); on or
//                           unset: native code; anything else keeps the tape
//                           and the one line names the mistake
//   RB_NATIVE_CC            the C compiler (default: cc on the PATH)
//   RB_NATIVE_CACHE         the cache folder (default:
//                           $XDG_CACHE_HOME/rollbench, else ~/.cache/rollbench,
//                           else a private mkdtemp folder for the process)
// A cache entry is keyed by the generated source, the compiler's identity and
// version, the flags and the code generator's version. The folder must be this
// user's alone, and an entry is authenticated with the folder's secret before
// it is loaded (native_cache.hpp; a forged, corrupted or stale one is rebuilt,
// never loaded), then checked against the tape at a few points. When no
// native code can be had, the tape (or, for a formula too big for the tape,
// the stack interpreter) runs and one line on stderr says which and why, once
// per process.
#include <memory>
#include <string>

namespace rb {

struct FormulaTape;

// The compiled programs of one formula (full jet, and slopes without f).
struct NativeFormula {
  using Function = void (*)(double x, double y, double* out);
  Function full = nullptr;
  Function slopes = nullptr;
  std::shared_ptr<void> library;  // keeps the shared object loaded

  explicit operator bool() const { return full != nullptr; }
};

struct NativeSettings {
  bool enabled = true;
  std::string compiler = "cc";
  std::string cache_dir;
  std::string refusal;  // why enabled is false, when not RB_NATIVE_FORMULA=off
  static const NativeSettings& from_environment();
};

// How compile_native went, for the one line and for tests.
enum class NativeOutcome { cached, built, disabled, unavailable };

struct NativeResult {
  NativeFormula code;  // empty unless cached or built
  NativeOutcome outcome;
  std::string why;  // for disabled and unavailable: why, for the one line
};

// The native code for a usable tape (tape.usable()); never throws.
NativeResult compile_native(const FormulaTape& tape, const NativeSettings& settings);

}  // namespace rb

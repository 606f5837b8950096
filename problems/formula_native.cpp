// Native landscapes (formula_native.hpp): the tape's C source compiled by the
// system compiler into a cached shared object, verified, then loaded.
//
// A cache entry is one file, <folder>/f<hash of key>.so: the shared object
// followed by a trailer with the full key and an HMAC under the folder's
// secret (native_cache.hpp; ELF ignores bytes past its sections). The
// entry is read from a checked descriptor and verified in memory; only
// those bytes are loaded, from a sealed memfd, so nothing another user
// wrote and nothing changed after the check can run. A forged, stale or
// damaged entry is rebuilt; a folder or entry that is not this user's alone
// is refused and the tape runs. Entries are written under a fresh name and
// renamed into place, so readers never see half a file.
#include "problems/formula_native.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string_view>
#include <vector>

#include "problems/formula.hpp"
#include "problems/formula_codegen.hpp"
#include "problems/formula_tape.hpp"
#include "problems/native_cache.hpp"

extern char** environ;

namespace rb {
namespace {

#ifndef RB_NATIVE_MARCH
#define RB_NATIVE_MARCH "-march=x86-64-v2"
#endif

// no contraction: a fused multiply-add would round differently from the tape;
// -fno-plt: libm's functions (sincos) called through the GOT, without the
// PLT's jump (callgrind: 8 instructions a step of rkmk4 fewer)
const std::vector<std::string> kFlags = {
    "-O2", "-fPIC", "-fno-plt", "-shared", "-ffp-contract=off", "-fno-math-errno", RB_NATIVE_MARCH};

// names the entry's file only: the HMAC, not this hash, authenticates it
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 1469598103934665603ull) {
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// Runs argv (no shell) with stdin and stderr on /dev/null and stdout into
// *out through a pipe (or /dev/null); the exit status, or -1 if it could not
// start. A temp_folder becomes the child's TMPDIR (TMP and TEMP too), so
// that what the compiler makes for itself (cc1's assembly, as's object,
// under names it opens again) goes there, not into a shared $TMPDIR.
int run_process(const std::vector<std::string>& args, std::string* out = nullptr, const std::string& temp_folder = "") {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> own_environment;
  std::vector<char*> envp;
  if (!temp_folder.empty()) {
    for (char** e = environ; *e; ++e) {
      const std::string_view entry(*e);
      if (!entry.starts_with("TMPDIR=") && !entry.starts_with("TMP=") && !entry.starts_with("TEMP="))
        envp.push_back(*e);
    }
    for (const char* key : {"TMPDIR=", "TMP=", "TEMP="}) own_environment.push_back(key + temp_folder);
    for (std::string& entry : own_environment) envp.push_back(entry.data());
    envp.push_back(nullptr);
  }
  int ends[2] = {-1, -1};
  if (out && pipe2(ends, O_CLOEXEC) != 0) return -1;
  const UniqueFd read_end(ends[0]);
  UniqueFd write_end(ends[1]);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (out) posix_spawn_file_actions_adddup2(&actions, write_end.get(), 1);
  else posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int started = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.empty() ? environ : envp.data());
  posix_spawn_file_actions_destroy(&actions);
  write_end = UniqueFd();  // the child holds its copy: EOF when it exits
  if (started != 0) return -1;
  char buf[4096];
  while (out) {
    const ssize_t got = ::read(read_end.get(), buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    out->append(buf, static_cast<std::size_t>(got));
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `compiler --version` through a pipe (no file), the compiler's identity in
// the key; empty if it does not run. Once per compiler and process.
std::string compiler_identity(const std::string& compiler) {
  static std::mutex mutex;
  static std::map<std::string, std::string> known;
  const std::lock_guard lock(mutex);
  if (const auto found = known.find(compiler); found != known.end()) return found->second;
  std::string identity;
  if (run_process({compiler, "--version"}, &identity) != 0) identity.clear();
  return known[compiler] = identity;
}

// Compiles source in a fresh private subfolder and seals the object as the
// entry name; the object, or empty on any failure.
std::string build_entry(const CacheFolder& folder, const std::string& name, const std::string& source,
                        const std::string& key, const std::string& compiler) {
  const std::optional<CacheFolder> work = make_private_subfolder(folder, "build.");
  if (!work) return {};
  PrivateFile c_file = create_private_file(*work, "formula.", ".c");
  std::string object;
  if (c_file.fd && write_all(c_file.fd.get(), source)) {
    c_file.fd = UniqueFd();
    std::vector<std::string> args = {compiler};
    args.insert(args.end(), kFlags.begin(), kFlags.end());
    args.insert(args.end(), {"-o", child_path(*work, "formula.so"), child_path(*work, c_file.name), "-lm"});
    if (run_process(args, nullptr, child_path(*work, ".")) != 0 || !read_own_output(*work, "formula.so", object))
      object.clear();
  }
  if (!c_file.name.empty()) ::unlinkat(work->fd.get(), c_file.name.c_str(), 0);
  ::unlinkat(work->fd.get(), "formula.so", 0);
  ::unlinkat(folder.fd.get(), work->path.substr(folder.path.size() + 1).c_str(), AT_REMOVEDIR);
  if (object.empty()) return {};
  PrivateFile entry = create_private_file(folder, name + ".", ".tmp");
  if (!entry.fd) return {};
  const bool written = write_all(entry.fd.get(), seal_entry(object, key, folder.secret));
  entry.fd = UniqueFd();
  // atomic: readers see the old entry or the new
  if (!written || ::renameat(folder.fd.get(), entry.name.c_str(), folder.fd.get(), name.c_str()) != 0) {
    ::unlinkat(folder.fd.get(), entry.name.c_str(), 0);
    return {};
  }
  return object;
}

// Loads exactly these (verified) bytes: copied into a memfd sealed against
// any change, then opened through /proc/self/fd. The memfd stays open while
// the library is loaded, so no two loaded libraries share that name (dlopen
// would hand back the first for the second).
NativeFormula load_object(std::string_view object, std::string& why) {
  UniqueFd fd(memfd_create("rollbench-native-formula", MFD_CLOEXEC | MFD_ALLOW_SEALING));
  constexpr int kSeals = F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE | F_SEAL_SEAL;
  if (!fd || !write_all(fd.get(), object) || fcntl(fd.get(), F_ADD_SEALS, kSeals) != 0) {
    why = std::string("cannot copy the native code into a sealed memfd (") + std::strerror(errno) + ")";
    return {};
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd.get());
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* error = dlerror();
    why = std::string("cannot load the native code (") + (error ? error : "dlopen failed") + ")";
    return {};
  }
  NativeFormula code;
  code.library = std::shared_ptr<void>(handle, [kept = fd.release()](void* h) {
    dlclose(h);
    ::close(kept);
  });
  code.full = reinterpret_cast<NativeFormula::Function>(dlsym(handle, "rb_formula_full"));
  code.slopes = reinterpret_cast<NativeFormula::Function>(dlsym(handle, "rb_formula_slopes"));
  if (!code.full || !code.slopes) {
    why = "the native code lacks its functions";
    return {};
  }
  return code;
}

bool same_bits(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

// The loaded code gives the tape's bits at a few points: a last guard
// against loading the wrong entry.
bool agrees_with_tape(const NativeFormula& code, const FormulaTape& tape) {
  const double points[][2] = {{0.3, -0.7}, {1.1, 0.45}, {-2.5, 1.9}};
  for (const auto& p : points) {
    double full[6], slopes[6];
    code.full(p[0], p[1], full);
    code.slopes(p[0], p[1], slopes);
    const Jet2<double> a = tape.full.run(p[0], p[1]), b = tape.slopes.run(p[0], p[1]);
    const double want_full[6] = {a.f, a.fx, a.fy, a.fxx, a.fxy, a.fyy};
    const double want_slopes[6] = {b.f, b.fx, b.fy, b.fxx, b.fxy, b.fyy};
    for (int i = 0; i < 6; ++i)
      if (!same_bits(full[i], want_full[i]) || !same_bits(slopes[i], want_slopes[i])) return false;
  }
  return true;
}

}  // namespace

const NativeSettings& NativeSettings::from_environment() {
  static const NativeSettings settings = [] {
    NativeSettings s;
    // anything but unset, "on" or "off" is a mistake: the tape, and the one line says so
    const std::string mode = std::getenv("RB_NATIVE_FORMULA") ? std::getenv("RB_NATIVE_FORMULA") : "";
    s.enabled = mode.empty() || mode == "on";
    if (!s.enabled && mode != "off") s.refusal = "RB_NATIVE_FORMULA='" + mode + "' is neither on nor off";
    if (const char* cc = std::getenv("RB_NATIVE_CC"); cc && *cc) s.compiler = cc;
    const char* dir = std::getenv("RB_NATIVE_CACHE");
    // (switched off, no private folder is made)
    if (dir && *dir) s.cache_dir = dir;
    else if (s.enabled) s.cache_dir = default_cache_folder(std::getenv("XDG_CACHE_HOME"), std::getenv("HOME"));
    return s;
  }();
  return settings;
}

NativeResult compile_native(const FormulaTape& tape, const NativeSettings& settings) {
  if (!settings.enabled)
    return {{}, NativeOutcome::disabled, settings.refusal.empty() ? "RB_NATIVE_FORMULA=off" : settings.refusal};
  if (!tape.usable()) return {{}, NativeOutcome::unavailable, "the formula is too long or too deep for the tape"};
  const std::string identity = compiler_identity(settings.compiler);
  if (identity.empty()) return {{}, NativeOutcome::unavailable, "no C compiler '" + settings.compiler + "'"};

  const std::string source = formula_c_source(tape);
  std::string key = "rollbench native formula, generator " + std::to_string(kFormulaCodegenVersion) + "\ncompiler " +
                    settings.compiler + ": " + identity + "flags";
  for (const std::string& f : kFlags) key += " " + f;
  key += "\n" + source;

  // one load per cache entry and process
  const std::string name = "f" + hex(fnv1a(key)) + ".so";
  const std::string where = settings.cache_dir + "/" + name;
  static std::mutex mutex;
  static std::map<std::string, std::pair<std::string, NativeFormula>> loaded;  // where -> key, code
  const std::lock_guard lock(mutex);
  if (const auto found = loaded.find(where); found != loaded.end() && found->second.first == key)
    return {found->second.second, NativeOutcome::cached, ""};

  std::string why;
  const std::optional<CacheFolder> folder = open_cache_folder(settings.cache_dir, why);
  if (!folder) return {{}, NativeOutcome::unavailable, why};
  std::string entry, object;
  const EntryRead read = read_cache_file(*folder, name, entry, why);
  if (read == EntryRead::refused) return {{}, NativeOutcome::unavailable, why};
  NativeOutcome outcome = NativeOutcome::cached;
  if (const auto verified = open_sealed_entry(entry, key, folder->secret)) {
    object = *verified;
  } else {  // missing, or forged, stale or damaged: never loaded
    object = build_entry(*folder, name, source, key, settings.compiler);
    if (object.empty()) return {{}, NativeOutcome::unavailable, "the C compiler '" + settings.compiler + "' failed"};
    outcome = NativeOutcome::built;
  }
  NativeFormula code = load_object(object, why);
  if (!code) return {{}, NativeOutcome::unavailable, why};
  if (!agrees_with_tape(code, tape)) return {{}, NativeOutcome::unavailable, "the native code disagrees with the tape"};
  loaded[where] = {key, code};
  return {code, outcome, ""};
}

NativeOutcome Formula::compile_native(const NativeSettings& settings) {
  NativeResult result = rb::compile_native(tape_, settings);
  native_ = result.code;
  return result.outcome;
}

bool Formula::compile_native() {
  const NativeResult result = rb::compile_native(tape_, NativeSettings::from_environment());
  native_ = result.code;
  if (native_) return true;
  // the line names the evaluator that runs instead, once per process each:
  // the tape, or for a formula too long or deep for it the stack interpreter
  static std::atomic<bool> said_tape{false}, said_stack{false};
  if (tape_.usable()) {
    if (!said_tape.exchange(true))
      std::fprintf(stderr, "rollbench: landscape formulas run on the tape, not as native code (%s)\n",
                   result.why.c_str());
  } else if (!said_stack.exchange(true)) {
    std::fprintf(stderr,
                 "rollbench: a landscape formula runs on the stack interpreter, neither on the tape nor as native "
                 "code (it is too long or too deep for the tape: %zu instructions, stack depth %zu)\n",
                 program_.size(), max_stack_);
  }
  return false;
}

}  // namespace rb

// Native landscapes (formula_native.hpp): the tape's C source compiled by the
// system compiler into a cached shared object, verified, then loaded.
//
// A cache entry is one file, <folder>/f<hash of key>.so, the shared object
// followed by a trailer: the full key, its length, an FNV-1a checksum of all
// bytes before the checksum, and a magic word. ELF ignores bytes past its
// sections, so the file loads as it is; before it loads, the trailer must
// hold this very key and the checksum must match, or the entry is rebuilt.
// Entries are written under a unique name and renamed into place, so readers
// never see half a file.
#include "problems/formula_native.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include "problems/formula.hpp"
#include "problems/formula_codegen.hpp"
#include "problems/formula_tape.hpp"

extern char** environ;

namespace rb {
namespace {

constexpr char kMagic[9] = "RBNATIV1";

#ifndef RB_NATIVE_MARCH
#define RB_NATIVE_MARCH "-march=x86-64-v2"
#endif

// no contraction: a fused multiply-add would round differently from the tape
const std::vector<std::string> kFlags = {"-O2", "-fPIC", "-shared", "-ffp-contract=off", "-fno-math-errno",
                                         RB_NATIVE_MARCH};

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 1469598103934665603ull) {
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// Runs argv (no shell) with stdout into out_fd (or /dev/null) and stderr into
// /dev/null; the exit status, or -1 if it could not start.
int run_process(const std::vector<std::string>& args, int out_fd = -1) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (out_fd >= 0) posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
  else posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int started = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return in ? s.str() : std::string();
}

// `compiler --version`, the compiler's identity in the key; empty if it
// does not run. Once per compiler and process.
std::string compiler_identity(const std::string& compiler, const std::filesystem::path& folder) {
  static std::mutex mutex;
  static std::map<std::string, std::string> known;
  const std::lock_guard lock(mutex);
  if (const auto found = known.find(compiler); found != known.end()) return found->second;
  std::string identity;
  const std::filesystem::path out = folder / ("version." + std::to_string(getpid()) + ".txt");
  const int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd >= 0) {
    if (run_process({compiler, "--version"}, fd) == 0) identity = read_file(out);
    close(fd);
    std::error_code ignored;
    std::filesystem::remove(out, ignored);
  }
  return known[compiler] = identity;
}

void put_u64(std::string& s, std::uint64_t v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }
std::uint64_t get_u64(const std::string& s, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, s.data() + at, sizeof v);
  return v;
}

std::string trailer(const std::string& object, const std::string& key) {
  std::string t = key;
  put_u64(t, key.size());
  put_u64(t, fnv1a(t, fnv1a(object)));
  return t.append(kMagic, 8);
}

// The entry at path holds this key and is intact.
bool entry_valid(const std::filesystem::path& path, const std::string& key) {
  const std::string bytes = read_file(path);
  const std::size_t fixed = 24;
  if (bytes.size() < fixed + key.size() || bytes.compare(bytes.size() - 8, 8, kMagic, 8) != 0) return false;
  if (get_u64(bytes, bytes.size() - 24) != key.size()) return false;
  const std::size_t key_at = bytes.size() - fixed - key.size();
  if (bytes.compare(key_at, key.size(), key) != 0) return false;
  const std::string_view before_sum(bytes.data(), bytes.size() - 16);
  return get_u64(bytes, bytes.size() - 16) == fnv1a(before_sum);
}

std::atomic<unsigned> unique_counter{0};

// Compiles source into the entry at path; false on any failure.
bool build_entry(const std::filesystem::path& path, const std::string& source, const std::string& key,
                 const std::string& compiler) {
  const std::string stem = path.string() + ".tmp." + std::to_string(getpid()) + "." +
                           std::to_string(unique_counter.fetch_add(1));
  const std::string c_file = stem + ".c", so_file = stem + ".so";
  bool ok = false;
  {
    std::ofstream out(c_file, std::ios::binary);
    out << source;
    ok = static_cast<bool>(out.flush());
  }
  if (ok) {
    std::vector<std::string> args = {compiler};
    args.insert(args.end(), kFlags.begin(), kFlags.end());
    args.insert(args.end(), {"-o", so_file, c_file, "-lm"});
    ok = run_process(args) == 0;
  }
  if (ok) {
    const std::string object = read_file(so_file);
    std::ofstream out(so_file, std::ios::binary | std::ios::app);
    ok = !object.empty() && static_cast<bool>(out << trailer(object, key)) && static_cast<bool>(out.flush());
  }
  std::error_code error;
  std::filesystem::remove(c_file, error);
  if (ok) std::filesystem::rename(so_file, path, error);  // atomic: readers see the old entry or the new
  ok = ok && !error;
  if (!ok) std::filesystem::remove(so_file, error);
  return ok && entry_valid(path, key);
}

NativeFormula load_entry(const std::filesystem::path& path) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) return {};
  NativeFormula code;
  code.library = std::shared_ptr<void>(handle, [](void* h) { dlclose(h); });
  code.full = reinterpret_cast<NativeFormula::Function>(dlsym(handle, "rb_formula_full"));
  code.slopes = reinterpret_cast<NativeFormula::Function>(dlsym(handle, "rb_formula_slopes"));
  if (!code.full || !code.slopes) return {};
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

std::filesystem::path default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "rollbench";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache/rollbench";
  return std::filesystem::temp_directory_path() / ("rollbench-cache-" + std::to_string(getuid()));
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
    s.cache_dir = dir && *dir ? std::string(dir) : default_cache_dir().string();
    return s;
  }();
  return settings;
}

NativeResult compile_native(const FormulaTape& tape, const NativeSettings& settings) {
  if (!settings.enabled)
    return {{}, NativeOutcome::disabled, settings.refusal.empty() ? "RB_NATIVE_FORMULA=off" : settings.refusal};
  if (!tape.usable()) return {{}, NativeOutcome::unavailable, "the formula is too long to lower"};
  const std::filesystem::path folder = settings.cache_dir;
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) return {{}, NativeOutcome::unavailable, "cannot create the cache folder " + folder.string()};
  const std::string identity = compiler_identity(settings.compiler, folder);
  if (identity.empty()) return {{}, NativeOutcome::unavailable, "no C compiler '" + settings.compiler + "'"};

  const std::string source = formula_c_source(tape);
  std::string key = "rollbench native formula, generator " + std::to_string(kFormulaCodegenVersion) +
                    "\ncompiler " + settings.compiler + ": " + identity + "flags";
  for (const std::string& f : kFlags) key += " " + f;
  key += "\n" + source;

  // one load per cache entry and process
  const std::filesystem::path path = folder / ("f" + hex(fnv1a(key)) + ".so");
  static std::mutex mutex;
  static std::map<std::string, std::pair<std::string, NativeFormula>> loaded;  // path -> key, code
  const std::lock_guard lock(mutex);
  if (const auto found = loaded.find(path.string()); found != loaded.end() && found->second.first == key)
    return {found->second.second, NativeOutcome::cached, ""};

  NativeOutcome outcome = NativeOutcome::cached;
  if (!entry_valid(path, key)) {
    if (!build_entry(path, source, key, settings.compiler))
      return {{}, NativeOutcome::unavailable, "the C compiler '" + settings.compiler + "' failed"};
    outcome = NativeOutcome::built;
  }
  NativeFormula code = load_entry(path);
  if (!code) return {{}, NativeOutcome::unavailable, "cannot load " + path.string()};
  if (!agrees_with_tape(code, tape)) return {{}, NativeOutcome::unavailable, "the native code disagrees with the tape"};
  loaded[path.string()] = {key, code};
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
  if (!native_) {
    static std::atomic<bool> said{false};
    if (!said.exchange(true))
      std::fprintf(stderr, "rollbench: landscape formulas run on the tape, not as native code (%s)\n",
                   result.why.c_str());
  }
  return is_native();
}

}  // namespace rb

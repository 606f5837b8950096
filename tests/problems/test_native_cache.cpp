// The native-formula cache's trust (problems/native_cache.hpp, docs/native-cache.md): a
// forged entry is rebuilt, never loaded; a folder, entry or secret that is
// not this user's alone is refused with the one line and the tape runs;
// links planted at the old predictable temporary names are not followed; and
// without HOME the cache is a private mkdtemp folder, not a shared name.
// Each of these was possible before (d44d9b5): the test fails there.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "problems/formula.hpp"
#include "problems/formula_codegen.hpp"
#include "problems/native_cache.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;

#define SKIP_IF_SWITCHED_OFF() \
  if (!NativeSettings::from_environment().enabled) GTEST_SKIP() << "RB_NATIVE_FORMULA=off"
#define SKIP_UNLESS_ROOT() \
  if (geteuid() != 0) GTEST_SKIP() << "needs root to make a file of another user"

constexpr uid_t kNobody = 65534;
const std::string kText = "0.1*sin(x*y) + 0.3*x - 0.05*y^2";

// a folder of this test alone (not made), removed with its contents at the end
class Folder {
 public:
  explicit Folder(const std::string& name)
      : path_(fs::temp_directory_path() / ("rb_ncache_" + name + "_" + std::to_string(getpid()))) {
    fs::remove_all(path_);
  }
  ~Folder() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }
  std::string str() const { return path_.string(); }
  NativeSettings settings(const std::string& compiler = "cc") const {
    NativeSettings s;
    s.cache_dir = str();
    s.compiler = compiler;
    return s;
  }
  // made 0700, as this user's, with its secret
  void make() const {
    std::string why;
    ASSERT_TRUE(open_cache_folder(str(), why)) << why;
  }

 private:
  fs::path path_;
};

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_all_to(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// the one entry (f<hash>.so) in a folder
fs::path entry_in(const fs::path& folder) {
  for (const auto& e : fs::directory_iterator(folder))
    if (e.path().extension() == ".so") return e.path();
  return {};
}

void put_u64(std::string& s, std::uint64_t v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }

// the key a sealed entry carries: ... key, u64 key length, 32-byte MAC, magic
std::string key_of(const std::string& entry) {
  std::uint64_t n = 0;
  std::memcpy(&n, entry.data() + entry.size() - 48, sizeof n);
  return entry.substr(entry.size() - 48 - n, n);
}

// d44d9b5's trailer, which anyone could recompute: key, length, FNV-1a of all before, magic
std::string old_style_trailer(const std::string& object, const std::string& key) {
  std::string t = key;
  put_u64(t, key.size());
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : object + t) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  put_u64(t, h);
  return t.append("RBNATIV1", 8);
}

testing::CliOutcome run_with_env(const std::string& env, const std::string& args) {
  const fs::path out = testing::cli_temp_file("nc-stdout"), err = testing::cli_temp_file("nc-stderr");
  const std::string command =
      "env " + env + " " + RB_ROLLBENCH_EXE + " " + args + " > " + out.string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, testing::slurp(out), testing::slurp(err)};
}

std::string trajectory_args() {
  return std::string("trajectory ") + RB_TEST_DATA +
         "/stop-domain.json --integrator rk4 --h 0.01 --t-end 0.1 "
         "--dt-out 0.1 --out " +
         testing::cli_temp_file("nc.csv").string();
}

TEST(NativeCache, HmacSha256GivesRfc4231sTestVectors) {
  auto hex = [](const std::array<unsigned char, 32>& mac) {
    std::string s;
    for (const unsigned char b : mac) {
      char two[3];
      std::snprintf(two, sizeof two, "%02x", b);
      s += two;
    }
    return s;
  };
  // RFC 4231, test cases 1, 2 and 6 (a key longer than the block)
  EXPECT_EQ(hex(hmac_sha256(std::string(20, '\x0b'), "Hi There")),
            "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
  EXPECT_EQ(hex(hmac_sha256("Jefe", "what do ya want for nothing?")),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
  EXPECT_EQ(hex(hmac_sha256(std::string(131, '\xaa'), "Test Using Larger Than Block-Size Key - Hash Key First")),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
}

TEST(NativeCache, ASealedEntryOpensOnlyWithItsKeyAndSecret) {
  const std::string secret(32, 's'), object =
                                         "\x7f"
                                         "ELF and the rest";
  const std::string entry = seal_entry(object, "the key", secret);
  ASSERT_TRUE(open_sealed_entry(entry, "the key", secret));
  EXPECT_EQ(*open_sealed_entry(entry, "the key", secret), object);
  EXPECT_FALSE(open_sealed_entry(entry, "the kez", secret));
  EXPECT_FALSE(open_sealed_entry(entry, "the key", std::string(32, 't')));
  std::string flipped = entry;
  flipped[3] ^= 1;
  EXPECT_FALSE(open_sealed_entry(flipped, "the key", secret));
  EXPECT_FALSE(open_sealed_entry(entry.substr(1), "the key", secret));
  EXPECT_FALSE(open_sealed_entry(object + old_style_trailer(object, "the key"), "the key", secret));
}

// A library that gives the formula's bits, so it would pass the check
// against the tape, and whose constructor leaves a marker when loaded.
TEST(NativeCache, AForgedEntryIsRebuiltNeverLoaded) {
  SKIP_IF_SWITCHED_OFF();
  const Folder genuine("genuine"), work("forge");
  Formula f = Formula::parse(kText);
  ASSERT_EQ(f.compile_native(genuine.settings()), NativeOutcome::built);
  const fs::path real_entry = entry_in(genuine.path());
  const std::string key = key_of(read_all(real_entry));
  ASSERT_NE(key.find("rollbench native formula"), std::string::npos);

  fs::create_directories(work.path());
  const fs::path marker = work.path() / "constructor-ran", c_file = work.path() / "evil.c",
                 so = work.path() / "evil.so";
  write_all_to(c_file, formula_c_source(f.tape()) +
                           "\n#include <fcntl.h>\n#include <unistd.h>\n"
                           "__attribute__((constructor)) static void rb_forged(void) {\n  int fd = open(\"" +
                           marker.string() + "\", O_CREAT | O_WRONLY, 0600);\n  if (fd >= 0) close(fd);\n}\n");
  ASSERT_EQ(std::system(
                ("cc -O2 -fPIC -shared -ffp-contract=off -o " + so.string() + " " + c_file.string() + " -lm").c_str()),
            0);
  const std::string evil = read_all(so);
  const std::string real_trailer = read_all(real_entry).substr(read_all(real_entry).size() - 48 - key.size());
  const struct {
    const char* name;
    std::string bytes;
  } forgeries[] = {
      {"old-trailer", evil + old_style_trailer(evil, key)},              // d44d9b5 loaded this one
      {"copied-mac", evil + real_trailer},                               // a genuine entry's MAC on other bytes
      {"guessed-secret", seal_entry(evil, key, std::string(32, '\0'))},  // sealed under a guessed secret
  };
  for (const auto& forgery : forgeries) {
    const Folder cache(std::string("forged_") + forgery.name);
    cache.make();
    write_all_to(cache.path() / real_entry.filename(), forgery.bytes);
    fs::permissions(cache.path() / real_entry.filename(), fs::perms::owner_read | fs::perms::owner_write);
    Formula g = Formula::parse(kText);
    EXPECT_EQ(g.compile_native(cache.settings()), NativeOutcome::built) << forgery.name;
    EXPECT_TRUE(g.is_native()) << forgery.name;
    EXPECT_FALSE(fs::exists(marker)) << forgery.name << ": the forged library's constructor ran";
    EXPECT_NE(read_all(cache.path() / real_entry.filename()), forgery.bytes) << forgery.name << " was not rebuilt";
  }
  // the forgery is real: loaded, its constructor runs
  void* handle = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr);
  EXPECT_TRUE(fs::exists(marker));
  dlclose(handle);
}

// compile_native refuses with why; Formula::compile_native() prints it
void expect_refused(const Folder& cache, const std::string& why) {
  Formula f = Formula::parse(kText);
  const NativeResult r = compile_native(f.tape(), cache.settings());
  EXPECT_EQ(r.outcome, NativeOutcome::unavailable);
  EXPECT_FALSE(r.code);
  EXPECT_EQ(r.why, why);
  EXPECT_EQ(f.compile_native(cache.settings()), NativeOutcome::unavailable);
  EXPECT_FALSE(f.is_native());
  EXPECT_DOUBLE_EQ(f.eval(1.0, 0.0).fx, 0.1 * 0.0 + 0.3);  // the tape runs
}

TEST(NativeCache, AFolderOfAnotherUserIsRefusedWithTheLineAndTheTapeRuns) {
  SKIP_IF_SWITCHED_OFF();
  SKIP_UNLESS_ROOT();
  const Folder cache("foreign");
  ASSERT_EQ(mkdir(cache.path().c_str(), 0700), 0);
  ASSERT_EQ(chown(cache.path().c_str(), kNobody, kNobody), 0);
  const std::string why = "the cache folder '" + cache.str() + "' is owned by uid 65534, not by this user (uid 0)";
  expect_refused(cache, why);
  EXPECT_TRUE(fs::is_empty(cache.path())) << "nothing is written into it";
  // from the command line: the run goes on, on the tape, and the one line says why
  const testing::CliOutcome o = run_with_env("RB_NATIVE_CACHE=" + cache.str(), trajectory_args());
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err, "rollbench: landscape formulas run on the tape, not as native code (" + why + ")\n");
}

TEST(NativeCache, AFolderWritableByGroupOrOthersIsRefused) {
  SKIP_IF_SWITCHED_OFF();
  for (const mode_t mode : {0777, 0770, 0702}) {
    const Folder cache("writable");
    ASSERT_EQ(mkdir(cache.path().c_str(), 0700), 0);
    ASSERT_EQ(chmod(cache.path().c_str(), mode), 0);
    char octal[8];
    std::snprintf(octal, sizeof octal, "%04o", static_cast<unsigned>(mode));
    expect_refused(cache, "the cache folder '" + cache.str() + "' is writable by group or others (mode " + octal + ")");
  }
}

TEST(NativeCache, ASymlinkedFolderIsRefused) {
  SKIP_IF_SWITCHED_OFF();
  const Folder real("link_target"), cache("link");
  real.make();
  fs::create_directory_symlink(real.path(), cache.path());
  expect_refused(cache, "the cache folder '" + cache.str() + "' is a symbolic link or not a folder");
}

// a copy of a good cache (its secret and entry) in a fresh folder, spoiled,
// then refused with why(folder, entry)
void expect_copy_refused(const std::string& name,
                         const std::function<void(const fs::path& folder, const fs::path& entry)>& spoil,
                         const std::function<std::string(const fs::path& folder, const fs::path& entry)>& why) {
  const Folder genuine(name + "_genuine"), cache(name);
  Formula f = Formula::parse(kText);
  ASSERT_EQ(f.compile_native(genuine.settings()), NativeOutcome::built);
  ASSERT_EQ(mkdir(cache.path().c_str(), 0700), 0);
  const fs::path entry = cache.path() / entry_in(genuine.path()).filename();
  fs::copy_file(genuine.path() / "hmac-secret", cache.path() / "hmac-secret");
  fs::copy_file(entry_in(genuine.path()), entry);
  {  // unspoiled, the copy is a good cache (so the refusal below is the spoiling's)
    const Folder check(name + "_check");
    fs::copy(cache.path(), check.path());
    Formula g = Formula::parse(kText);
    ASSERT_EQ(g.compile_native(check.settings()), NativeOutcome::cached) << name;
  }
  spoil(cache.path(), entry);
  expect_refused(cache, why(cache.path(), entry));
}

TEST(NativeCache, AnEntryOrSecretNotThisUsersAloneIsRefused) {
  SKIP_IF_SWITCHED_OFF();
  expect_copy_refused(
      "entry_writable", [](const fs::path&, const fs::path& e) { fs::permissions(e, fs::perms::all); },
      [](const fs::path&, const fs::path& e) {
        return "the cache entry '" + e.string() + "' is writable by group or others (mode 0777)";
      });
  expect_copy_refused(
      "entry_symlink",
      [](const fs::path& folder, const fs::path& e) {
        fs::rename(e, folder / "elsewhere.so");
        fs::create_symlink(folder / "elsewhere.so", e);
      },
      [](const fs::path&, const fs::path& e) { return "the cache entry '" + e.string() + "' is a symbolic link"; });
  expect_copy_refused(
      "secret_readable",
      [](const fs::path& folder, const fs::path&) {
        fs::permissions(folder / "hmac-secret", fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
      },
      [](const fs::path& folder, const fs::path&) {
        return "the cache secret '" + (folder / "hmac-secret").string() + "' has mode 0640; a secret must be 0600";
      });
  if (geteuid() != 0) return;  // the rest needs another owner
  expect_copy_refused(
      "entry_foreign", [](const fs::path&, const fs::path& e) { ASSERT_EQ(chown(e.c_str(), kNobody, kNobody), 0); },
      [](const fs::path&, const fs::path& e) {
        return "the cache entry '" + e.string() + "' is owned by uid 65534, not by this user (uid 0)";
      });
  expect_copy_refused(
      "secret_foreign",
      [](const fs::path& folder, const fs::path&) {
        ASSERT_EQ(chown((folder / "hmac-secret").c_str(), kNobody, kNobody), 0);
      },
      [](const fs::path& folder, const fs::path&) {
        return "the cache secret '" + (folder / "hmac-secret").string() +
               "' is owned by uid 65534, not by this user (uid 0)";
      });
}

TEST(NativeCache, TheSecretIsMadeOnce0600AndKept) {
  const Folder cache("secret");
  cache.make();
  const fs::path secret = cache.path() / "hmac-secret";
  struct stat st {};
  ASSERT_EQ(lstat(secret.c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(st.st_uid, geteuid());
  ASSERT_EQ(lstat(cache.path().c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0700u) << "the folder is made 0700";
  const std::string first = read_all(secret);
  EXPECT_EQ(first.size(), 32u);
  cache.make();
  EXPECT_EQ(read_all(secret), first);
  EXPECT_EQ(std::distance(fs::directory_iterator(cache.path()), fs::directory_iterator()), 1) << "no temporary left";
}

// the compiler's output gets the umask's mode (0775 under umask 002, usual
// for users with their own group): it is made in a private 0700 subfolder, so
// it is trusted there, and the entry written from it is 0600
TEST(NativeCache, BuildsUnderAGroupWritableUmask) {
  SKIP_IF_SWITCHED_OFF();
  const Folder cache("umask");
  const mode_t old_mask = umask(002);
  Formula f = Formula::parse(kText + " + 0.01*y");
  const NativeOutcome outcome = f.compile_native(cache.settings());
  umask(old_mask);
  EXPECT_EQ(outcome, NativeOutcome::built);
  struct stat st {};
  ASSERT_EQ(lstat(entry_in(cache.path()).c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(std::distance(fs::directory_iterator(cache.path()), fs::directory_iterator()), 2)
      << "the entry and the secret; no build folder left behind";
}

// where cc is, for a compiler name this process has not run yet
std::string cc_on_path() {
  std::stringstream path(std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin");
  for (std::string dir; std::getline(path, dir, ':');)
    if (!dir.empty() && access((dir + "/cc").c_str(), X_OK) == 0) return dir;
  return {};
}

// d44d9b5 wrote version.<pid>.txt and <entry>.tmp.<pid>.<n>.c with
// predictable names, following a link planted there (as root, into any file)
TEST(NativeCache, LinksPlantedAtThePredictableTemporaryNamesAreNotFollowed) {
  SKIP_IF_SWITCHED_OFF();
  const Folder genuine("plant_genuine"), cache("plant"), victim_folder("plant_victim");
  Formula f = Formula::parse(kText);
  ASSERT_EQ(f.compile_native(genuine.settings()), NativeOutcome::built);
  const std::string entry = entry_in(genuine.path()).filename().string();
  fs::create_directories(victim_folder.path());
  const fs::path victim = victim_folder.path() / "victim";
  write_all_to(victim, "untouched");
  ASSERT_EQ(mkdir(cache.path().c_str(), 0700), 0);
  const std::string pid = std::to_string(getpid());
  fs::create_symlink(victim, cache.path() / ("version." + pid + ".txt"));
  for (int n = 0; n < 512; ++n)
    for (const char* ext : {".c", ".so"})
      fs::create_symlink(victim, cache.path() / (entry + ".tmp." + pid + "." + std::to_string(n) + ext));
  // a compiler name not run before in this process, so its --version is asked now
  const std::string dir = cc_on_path();
  ASSERT_FALSE(dir.empty()) << "no cc on the PATH";
  Formula g = Formula::parse(kText), h = Formula::parse(kText);
  EXPECT_EQ(g.compile_native(cache.settings()), NativeOutcome::built);
  EXPECT_EQ(h.compile_native(cache.settings(dir + "/./cc")), NativeOutcome::built);
  EXPECT_TRUE(g.is_native() && h.is_native());
  EXPECT_EQ(read_all(victim), "untouched");
  for (const auto& e : fs::directory_iterator(cache.path()))
    EXPECT_TRUE(e.is_symlink() || e.path().extension() == ".so" || e.path().filename() == "hmac-secret")
        << "left behind: " << e.path();
}

TEST(NativeCache, DefaultFolderWithoutHomeIsPrivateToTheProcess) {
  EXPECT_EQ(default_cache_folder("/x", "/h"), "/x/rollbench");
  EXPECT_EQ(default_cache_folder(nullptr, "/h"), "/h/.cache/rollbench");
  EXPECT_EQ(default_cache_folder("", "/h"), "/h/.cache/rollbench");
  const std::string mine = default_cache_folder(nullptr, nullptr);
  ASSERT_FALSE(mine.empty());
  EXPECT_EQ(default_cache_folder("", ""), mine) << "one folder per process";
  EXPECT_EQ(fs::path(mine).parent_path(), fs::temp_directory_path());
  EXPECT_EQ(fs::path(mine).filename().string().rfind("rollbench-cache-", 0), 0u);
  EXPECT_NE(fs::path(mine).filename().string(), "rollbench-cache-" + std::to_string(getuid()));
  struct stat st {};
  ASSERT_EQ(lstat(mine.c_str(), &st), 0);
  EXPECT_TRUE(S_ISDIR(st.st_mode));
  EXPECT_EQ(st.st_mode & 07777, 0700u);
  EXPECT_EQ(st.st_uid, geteuid());
}

TEST(NativeCache, WithoutHomeARunLeavesNoSharedFolderBehind) {
  SKIP_IF_SWITCHED_OFF();
  const Folder temp("nohome");
  ASSERT_EQ(mkdir(temp.path().c_str(), 0700), 0);
  const char* path = std::getenv("PATH");
  const testing::CliOutcome o = run_with_env(
      "-i PATH=" + std::string(path ? path : "/usr/bin:/bin") + " TMPDIR=" + temp.str(), trajectory_args());
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err, "") << "native code ran, from the private folder";
  // d44d9b5 left <TMPDIR>/rollbench-cache-<uid> for anyone to plant into
  EXPECT_TRUE(fs::is_empty(temp.path())) << "the private folder is removed at exit";
}

}  // namespace
}  // namespace rb

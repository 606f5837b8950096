// issue 57: outputs and caches are reached without following what others
// own (problems/safe_path.hpp), /dev/stdout is written through as a stream
// and never renamed over, an unwritable --out is refused before any run, and
// a report a full disk will not take is kept elsewhere
// (bench/lib/output_file.hpp).
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "bench/lib/output_file.hpp"
#include "bench/lib/reference.hpp"
#include "problems/input_error.hpp"
#include "problems/native_cache.hpp"
#include "problems/safe_path.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;
using testing::cli_temp_file;
using testing::CliTempFolder;
using testing::run_rollbench;
using testing::slurp;

constexpr uid_t kNobody = 65534;

std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The shared folder: S (root's, 1777), in it nobody's folder nob and
// two links of nobody's to a victim folder of the caller's, S/link and
// S/nob/link; the victim holds victimdir/report.json. Only root can hand a
// link to another uid (lchown); the tests skip otherwise.
struct SharedFolder {
  CliTempFolder base;
  fs::path shared = base.path() / "S", nob = shared / "nob", victim = base.path() / "victim";
  fs::path victim_report = victim / "victimdir" / "report.json";
  bool made = false;
  SharedFolder() {
    fs::create_directories(nob);
    fs::create_directories(victim_report.parent_path());
    std::ofstream(victim_report) << "keep";
    ::chmod(shared.c_str(), 01777);
    fs::create_symlink(victim, shared / "link");
    fs::create_symlink(victim, nob / "link");
    made = ::geteuid() == 0 && ::chown(nob.c_str(), kNobody, kNobody) == 0 &&
           ::lchown((shared / "link").c_str(), kNobody, kNobody) == 0 &&
           ::lchown((nob / "link").c_str(), kNobody, kNobody) == 0;
  }
  // the message for a path through link (S/link or S/nob/link)
  std::string refusal(const fs::path& link) const {
    const std::string folder_owner = link.parent_path() == nob ? "65534" : std::to_string(::geteuid());
    return "'" + link.string() + "' is a symbolic link owned by uid 65534 in a folder owned by uid " + folder_owner +
           "; not followed";
  }
  bool victim_untouched() const {
    return slurp(victim_report) == "keep" && names_in(victim) == std::vector<std::string>{"victimdir"} &&
           names_in(victim_report.parent_path()) == std::vector<std::string>{"report.json"};
  }
};

TEST(OutputPaths, ALinkOfAnotherUserInTheMiddleOfOutIsRefusedAndNothingIsWritten) {
  SharedFolder s;
  if (!s.made) GTEST_SKIP() << "needs root to hand links to uid 65534";
  for (const fs::path& link : {s.shared / "link", s.nob / "link"}) {
    const std::string out = (link / "victimdir" / "report.json").string();
    try {
      write_output_file(out, "overwritten", "out");
      ADD_FAILURE() << out << " was written";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "'out': cannot open '" + out + "' for writing (" + s.refusal(link) + ")");
    }
    // the command line, as in the issue: exit 2 before any run
    const auto cli = run_rollbench("trajectory plane --integrator rk4 --h 0.1 --out " + out);
    EXPECT_EQ(cli.code, 2) << cli.err;
    EXPECT_EQ(cli.err, "rollbench: 'out': cannot open '" + out + "' for writing (" + s.refusal(link) + ")\n");
    EXPECT_TRUE(s.victim_untouched());
  }
  EXPECT_EQ(names_in(s.shared), (std::vector<std::string>{"link", "nob"}));
}

TEST(OutputPaths, ALinkOfAnotherUserInTheMiddleOfCacheIsRefusedAndNothingIsCreated) {
  SharedFolder s;
  if (!s.made) GTEST_SKIP() << "needs root to hand links to uid 65534";
  for (const fs::path& link : {s.shared / "link", s.nob / "link"}) {
    const std::string cache = (link / "planted-cache" / "x").string();
    try {
      check_cache_folder(cache);
      ADD_FAILURE() << cache << " was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                "'cache': cannot use the cache folder '" + cache + "' (" + s.refusal(link) + ")");
    }
    std::string why;
    EXPECT_FALSE(open_cache_folder(cache, why));  // the native-formula cache
    EXPECT_EQ(why, "cannot create the cache folder '" + cache + "' (" + s.refusal(link) + ")");
    const auto cli = run_rollbench("run --scenes plane --integrators rk4 --h 0.1 --cache " + cache + " --out " +
                                   (s.base.path() / "report.json").string());
    EXPECT_EQ(cli.code, 2) << cli.err;
    EXPECT_EQ(cli.err, "rollbench: 'cache': cannot use the cache folder '" + cache + "' (" + s.refusal(link) + ")\n");
    EXPECT_TRUE(s.victim_untouched());
  }
  EXPECT_FALSE(fs::exists(s.base.path() / "report.json"));
  EXPECT_EQ(names_in(s.base.path()), (std::vector<std::string>{"S", "victim"}));  // no temporary either
}

// The caller's own links (and root's, such as /tmp's) are followed: the
// file lands where the link points, and the link stays a link.
TEST(OutputPaths, ALinkOfThisUserIsFollowed) {
  const CliTempFolder base;
  const fs::path real = base.path() / "real", mine = base.path() / "mine";
  fs::create_directories(real / "sub");
  fs::create_symlink("real", mine);  // relative, resolved from the link's folder
  fs::create_symlink(real / "sub", real / "to-sub");
  write_output_file((mine / "to-sub" / "x.csv").string(), "data", "out");
  EXPECT_EQ(slurp(real / "sub" / "x.csv"), "data");
  EXPECT_TRUE(fs::is_symlink(mine));
  const OpenedFolder made = open_folder((mine / "new" / "deeper").string(), MissingFolders::make);
  EXPECT_TRUE(made) << made.why();
  EXPECT_TRUE(fs::is_directory(real / "new" / "deeper"));
  // a loop of links ends, named as the kernel names it
  fs::create_symlink("loop-b", base.path() / "loop-a");
  fs::create_symlink("loop-a", base.path() / "loop-b");
  const OpenedFolder loop = open_folder((base.path() / "loop-a").string());
  EXPECT_FALSE(loop);
  EXPECT_EQ(loop.error, ELOOP);
}

// issue 57: `--out /dev/stdout > x.csv` turned the system's /dev/stdout into
// a regular file (the link was renamed over). Now the bytes go to descriptor
// 1, in order, and the link stays; tried on a link of the test's own first,
// then on the real /dev/stdout, /dev/fd/1 and /proc/self/fd/1.
TEST(OutputPaths, StandardOutputIsWrittenAsAStreamAndNeverRenamedOver) {
  const CliTempFolder base;
  const std::string expected_csv = [&] {
    const fs::path file = base.path() / "file.csv";
    EXPECT_EQ(run_rollbench("trajectory plane --integrator rk4 --h 0.01 --out " + file.string()).code, 0);
    return slurp(file);
  }();
  ASSERT_FALSE(expected_csv.empty());
  const fs::path fake = base.path() / "fake-stdout";
  fs::create_symlink("/proc/self/fd/1", fake);
  std::vector<std::string> outs = {fake.string()};
  const bool real_link = fs::is_symlink("/dev/stdout") && fs::read_symlink("/dev/stdout") == "/proc/self/fd/1";
  if (real_link) outs.insert(outs.end(), {"/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"});
  for (const std::string& out : outs) {
    const auto cli = run_rollbench("trajectory plane --integrator rk4 --h 0.01 --out " + out);
    EXPECT_EQ(cli.code, 0) << out << ": " << cli.err;
    EXPECT_EQ(cli.out.substr(0, expected_csv.size()), expected_csv) << out;  // the CSV, then the summary
    EXPECT_NE(cli.out.find("rk4 on plane: ok"), std::string::npos) << out;
  }
  EXPECT_TRUE(fs::is_symlink(fake));
  EXPECT_EQ(names_in(base.path()), (std::vector<std::string>{"fake-stdout", "file.csv"}));
  if (real_link && !fs::is_symlink("/dev/stdout")) {  // the old bug: put the system's link back
    ADD_FAILURE() << "/dev/stdout was replaced";
    fs::remove("/dev/stdout");
    fs::create_symlink("/proc/self/fd/1", "/dev/stdout");
  }
  // a report to standard output through the same link (run's --out)
  const auto run = run_rollbench("run --scenes plane --integrators rk4 --h 0.1 --out " + fake.string());
  EXPECT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out.rfind("{\n", 0), 0u);
  EXPECT_TRUE(fs::is_symlink(fake));
}

// A link to another descriptor (here standard error, a regular file when
// redirected) is refused: it is neither a regular file nor standard output.
TEST(OutputPaths, ALinkToAnotherDescriptorIsRefused) {
  const CliTempFolder base;
  const fs::path fake = base.path() / "fake-stderr";
  fs::create_symlink("/proc/self/fd/2", fake);
  const auto cli = run_rollbench("trajectory plane --integrator rk4 --h 0.1 --out " + fake.string());
  EXPECT_EQ(cli.code, 2);
  // the message last (a user without a home gets a note on the native-formula cache first)
  EXPECT_TRUE(cli.err.ends_with("rollbench: 'out': '" + fake.string() +
                                "' exists and is a link to a file descriptor other than standard output; outputs "
                                "are written only to regular files\n"))
      << cli.err;
  EXPECT_TRUE(fs::is_symlink(fake));
  EXPECT_EQ(names_in(base.path()), std::vector<std::string>{"fake-stderr"});
}

// issue 57: an unwritable --out on run was found after every reference and
// run. Now it is refused first: no progress line, the cache folder given to
// the same run never made; merge likewise before it reads a report.
TEST(OutputPaths, AnUnwritableOutIsRefusedBeforeAnyRun) {
  const CliTempFolder base;
  const fs::path cache = base.path() / "cache";
  const std::string out = "/nonexistent/dir/report.json";
  const auto run =
      run_rollbench("run --scenes plane --integrators rk4 --h 0.1 --cache " + cache.string() + " --out " + out);
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(run.err, "rollbench: 'out': cannot open '" + out + "' for writing\n");
  EXPECT_EQ(run.out, "");
  EXPECT_FALSE(fs::exists(cache));
  const auto merge = run_rollbench("merge " + (base.path() / "missing.json").string() + " --out " + out);
  EXPECT_EQ(merge.code, 2);
  EXPECT_EQ(merge.err, "rollbench: 'out': cannot open '" + out + "' for writing\n");
}

// A small file system of its own (tmpfs), filled: the test needs root to
// mount one and skips otherwise.
struct FullDisk {
  CliTempFolder base;
  fs::path mount = base.path() / "full", keep = base.path() / "keep";
  bool mounted = false;
  std::optional<std::string> old_tmpdir;
  FullDisk() {
    fs::create_directories(mount);
    fs::create_directories(keep);
    if (::geteuid() != 0 || ::mount("tmpfs", mount.c_str(), "tmpfs", 0, "size=64k") != 0) return;
    mounted = true;
    std::ofstream filler(mount / "filler");
    const std::string block(4096, 'x');
    for (int i = 0; i < 64 && filler; ++i) filler << block << std::flush;
    // the process's own CLI folder is made now, under the real TMPDIR, not in keep
    (void)cli_temp_file("");
    if (const char* t = std::getenv("TMPDIR")) old_tmpdir = t;
    ::setenv("TMPDIR", keep.c_str(), 1);  // where a lost output is kept (rollbench inherits it)
  }
  ~FullDisk() {
    if (!mounted) return;
    ::umount2(mount.c_str(), MNT_DETACH);
    if (old_tmpdir) ::setenv("TMPDIR", old_tmpdir->c_str(), 1);
    else ::unsetenv("TMPDIR");
  }
};

TEST(OutputPaths, AReportAFullDiskWillNotTakeIsKeptElsewhereAndSaysWhere) {
  FullDisk disk;
  if (!disk.mounted) GTEST_SKIP() << "needs root to mount a tmpfs";
  const fs::path target = disk.mount / "report.json";
  const std::string text(200000, 'r');
  std::string message;
  try {
    write_output_file(target.string(), text, "out", IfLost::keep_elsewhere);
    ADD_FAILURE() << "written on a full disk";
  } catch (const InputError& e) {
    message = e.what();
  }
  const std::string prefix = "'out': could not write '" + target.string() +
                             "' (write: No space left on device); its content is kept in '" + disk.keep.string() +
                             "/rollbench-kept-report.json.";
  EXPECT_EQ(message.substr(0, prefix.size()), prefix);
  ASSERT_EQ(names_in(disk.keep).size(), 1u);
  const fs::path kept = disk.keep / names_in(disk.keep)[0];
  EXPECT_EQ(message, prefix.substr(0, prefix.size() - std::string("rollbench-kept-report.json.").size()) +
                         kept.filename().string() + "'");
  EXPECT_EQ(slurp(kept), text);
  EXPECT_EQ((fs::status(kept).permissions() & fs::perms::all), fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(names_in(disk.mount), std::vector<std::string>{"filler"});  // no target, no temporary
  fs::remove(kept);

  // discarded (a cache entry): the error alone
  try {
    write_output_file(target.string(), text, "cache");
    ADD_FAILURE() << "written on a full disk";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "'cache': could not write '" + target.string() + "' (write: No space left on device)");
  }
  EXPECT_TRUE(fs::is_empty(disk.keep));

  // a whole sweep: exit 2, its report kept and named
  const auto run = run_rollbench("run --scenes plane --integrators rk4 --h 0.1 --out " + target.string());
  EXPECT_EQ(run.code, 2);
  ASSERT_EQ(names_in(disk.keep).size(), 1u) << run.err;
  const fs::path report = disk.keep / names_in(disk.keep)[0];
  EXPECT_NE(run.err.find("rollbench: 'out': could not write '" + target.string() +
                         "' (write: No space left on device); its content is kept in '" + report.string() + "'\n"),
            std::string::npos)
      << run.err;
  EXPECT_NE(slurp(report).find("\"runs\""), std::string::npos);
  EXPECT_EQ(names_in(disk.mount), std::vector<std::string>{"filler"});
}

}  // namespace
}  // namespace rb

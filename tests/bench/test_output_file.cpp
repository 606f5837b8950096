// OutputFile (bench/lib/output_file.hpp): a file replaces its target only
// whole; one that is not committed leaves the old file as it was and no
// temporary file behind; an unwritable place is refused at once.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "bench/lib/output_file.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;

struct Folder {
  fs::path path = fs::temp_directory_path() / ("rb-output-file-" + std::to_string(::getpid()));
  Folder() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Folder() { fs::remove_all(path); }
  std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(path), {})); }
};

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OutputFile, ACommittedFileReplacesTheTargetWhole) {
  Folder folder;
  const fs::path target = folder.path / "report.json";
  std::ofstream(target) << "old";
  {
    OutputFile file(target.string(), "out");
    file.stream() << "new report";
    EXPECT_EQ(read(target), "old");  // nothing of it shows before commit
    EXPECT_EQ(folder.entries(), 2u);
    file.commit();
  }
  EXPECT_EQ(read(target), "new report");
  EXPECT_EQ(folder.entries(), 1u);  // the temporary file became the target
}

TEST(OutputFile, AFailureBeforeCommitLeavesTheOldFileAndNoTemporary) {
  Folder folder;
  const fs::path target = folder.path / "report.json";
  std::ofstream(target) << "old";
  try {
    OutputFile file(target.string(), "out");
    file.stream() << "half a rep";
    throw std::runtime_error("the dump failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read(target), "old");
  EXPECT_EQ(folder.entries(), 1u);
}

TEST(OutputFile, AnUnwritablePlaceIsRefusedAtOnce) {
  Folder folder;
  for (const std::string& bad : std::vector<std::string>{"/nonexistent/dir/x.csv", folder.path.string() + "/"}) {
    try {
      OutputFile file(bad, "out");
      ADD_FAILURE() << bad << " was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "'out': cannot open '" + bad + "' for writing");
    }
  }
}

// issue 32: a FIFO (open would hang with no reader), a device, a folder, or
// a symlink planted at the output path pointing at one, is refused at once,
// naming the path; nothing is written there and no temporary is left.
TEST(OutputFile, ANonRegularTargetOrALinkToOneIsRefused) {
  Folder folder;
  const fs::path fifo = folder.path / "fifo", link = folder.path / "link", device_link = folder.path / "null";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink(fifo, link);
  fs::create_symlink("/dev/null", device_link);
  const std::vector<std::pair<std::string, std::string>> cases = {{fifo.string(), "a FIFO"},
                                                                  {link.string(), "a FIFO"},
                                                                  {"/dev/null", "a device"},
                                                                  {device_link.string(), "a device"},
                                                                  {folder.path.string(), "a folder"}};
  for (const auto& [target, kind] : cases) {
    try {
      OutputFile file(target, "out");
      ADD_FAILURE() << target << " was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                "'out': '" + target + "' exists and is " + kind + "; outputs are written only to regular files");
    }
  }
  EXPECT_EQ(folder.entries(), 3u);  // the FIFO and the two links, no temporary
  EXPECT_TRUE(fs::is_fifo(fifo));
}

// A symlink to a regular file is replaced by the new file; its old target is left as it was.
TEST(OutputFile, ALinkToARegularFileIsReplacedNotFollowed) {
  Folder folder;
  const fs::path victim = folder.path / "victim", link = folder.path / "out.json";
  std::ofstream(victim) << "keep";
  fs::create_symlink(victim, link);
  write_output_file(link.string(), "new", "out");
  EXPECT_EQ(read(victim), "keep");
  EXPECT_FALSE(fs::is_symlink(link));
  EXPECT_EQ(read(link), "new");
}

// issue 32, item 1, and issue 57: the file is made relative to its
// folder's descriptor, reached by the path rule (problems/safe_path.hpp): a
// folder that is a link of this user's is followed, one of another user's
// is refused naming it; "." and ".." are no file names; a folder swapped for
// a link to another after the open is never written through: the file lands
// in the folder that was opened.
TEST(OutputFile, TheFolderIsOpenedOnceAndNeverFollowed) {
  Folder folder;
  const fs::path real = folder.path / "real", link = folder.path / "link", foreign = folder.path / "foreign";
  fs::create_directories(real);
  fs::create_symlink(real, link);
  fs::create_symlink(real, foreign);
  const bool foreign_made = ::geteuid() == 0 && ::lchown(foreign.c_str(), 65534, 65534) == 0;
  std::vector<std::string> bad_paths = {(real / "..").string(), (real / ".").string()};
  if (foreign_made) bad_paths.push_back((foreign / "x.csv").string());
  for (const std::string& bad : bad_paths) {
    try {
      OutputFile file(bad, "out");
      ADD_FAILURE() << bad << " was taken";
    } catch (const InputError& e) {
      const std::string why = bad.starts_with(foreign.string())
                                  ? " ('" + foreign.string() +
                                        "' is a symbolic link owned by uid 65534 in a folder owned by uid 0; "
                                        "not followed)"
                                  : "";
      EXPECT_EQ(std::string(e.what()), "'out': cannot open '" + bad + "' for writing" + why);
    }
  }
  EXPECT_TRUE(fs::is_empty(real));
  write_output_file((link / "mine.csv").string(), "mine", "out");  // this user's link: followed
  EXPECT_EQ(read(real / "mine.csv"), "mine");
  EXPECT_TRUE(fs::is_symlink(link));
  fs::remove(real / "mine.csv");

  const fs::path moved = folder.path / "moved", elsewhere = folder.path / "elsewhere";
  fs::create_directories(elsewhere);
  OutputFile file((real / "x.csv").string(), "out");
  file.stream() << "data";
  fs::rename(real, moved);
  fs::create_symlink(elsewhere, real);
  file.commit();
  EXPECT_EQ(read(moved / "x.csv"), "data");
  EXPECT_TRUE(fs::is_empty(elsewhere));
}

}  // namespace
}  // namespace rb

// The command-line tests' temporary folder (tests/cli_run.hpp): what the
// tests write there goes with it when the process that made it ends, and a
// forked child ending does not take it away from its parent.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;
using testing::CliTempFolder;

TEST(CliTempFolder, IsAFreshFolderOfItsOwnInTheTemporaryFolder) {
  const CliTempFolder a, b;
  EXPECT_EQ(a.path().parent_path(), fs::temp_directory_path());
  EXPECT_TRUE(fs::is_directory(a.path()));
  EXPECT_TRUE(fs::is_empty(a.path()));
  EXPECT_NE(a.path(), b.path());
  EXPECT_EQ(a.path().filename().string().rfind("rb-cli-run-", 0), 0u) << a.path();
}

TEST(CliTempFolder, GoesWithWhatWasWrittenInItWhenItsOwnerEnds) {
  fs::path path;
  {
    const CliTempFolder folder;
    path = folder.path();
    std::ofstream(path / "out.csv") << "t\n";
    fs::create_directory(path / "sub");
    std::ofstream(path / "sub" / "report.json") << "{}";
  }
  EXPECT_FALSE(fs::exists(path)) << path;
}

TEST(CliTempFolder, StaysWhenAForkedChildEnds) {
  std::optional<CliTempFolder> folder(std::in_place);
  const fs::path path = folder->path();
  std::ofstream(path / "kept.txt") << "x";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    folder.reset();  // the child's copy ends; the folder is its parent's
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(fs::exists(path / "kept.txt"));
  folder.reset();
  EXPECT_FALSE(fs::exists(path));
}

TEST(CliTempFolder, CliTempFileNamesAFileInTheProcesssOneFolder) {
  const fs::path a = testing::cli_temp_file("a.json"), b = testing::cli_temp_file("b.json");
  EXPECT_EQ(a.parent_path(), b.parent_path());
  EXPECT_EQ(a.filename(), "a.json");
  EXPECT_TRUE(fs::is_directory(a.parent_path()));
  EXPECT_EQ(a.parent_path().parent_path(), fs::temp_directory_path());
}

}  // namespace
}  // namespace rb

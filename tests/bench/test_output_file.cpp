// OutputFile (bench/lib/output_file.hpp): a file replaces its target only
// whole; one that is not committed leaves the old file as it was and no
// temporary file behind; an unwritable place is refused at once.
#include <gtest/gtest.h>
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
  for (const std::string& bad :
       std::vector<std::string>{"/nonexistent/dir/x.csv", folder.path.string(), folder.path.string() + "/"}) {
    try {
      OutputFile file(bad, "out");
      ADD_FAILURE() << bad << " was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "'out': cannot open '" + bad + "' for writing");
    }
  }
}

TEST(OutputFile, ANonRegularTargetIsWrittenInPlace) {
  OutputFile file("/dev/null", "out");
  file.stream() << "gone";
  EXPECT_NO_THROW(file.commit());
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

}  // namespace
}  // namespace rb

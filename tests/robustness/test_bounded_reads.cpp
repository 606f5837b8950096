// issue 57, item 2: every input is read as a regular file of bounded size
// (problems/input_file.hpp), parsed within its limits (depth, stages, line
// length) checked before the work, and quoted in messages only as a short
// escaped excerpt. Each command runs under `timeout`: a FIFO that hung
// would fail the test instead of hanging the suite.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/tableau_file.hpp"
#include "problems/input_error.hpp"
#include "problems/input_file.hpp"
#include "problems/json_limits.hpp"
#include "problems/safe_name.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;
using testing::CliOutcome;
using testing::slurp;

const std::string kRegular = "; inputs are read only from regular files\n";

// `rollbench ARGS` killed after 20 s (exit -1 or 137 then): never a hang.
CliOutcome bounded_rollbench(const std::string& args) {
  const fs::path out = testing::cli_temp_file("bounded-stdout"), err = testing::cli_temp_file("bounded-stderr");
  const std::string command = "timeout -s KILL 20 " + std::string(RB_ROLLBENCH_EXE) + " " + args + " > " +
                              out.string() + " 2> " + err.string() + " < /dev/null";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// A folder of its own for one test, with a FIFO, a sub-folder and a 1 GiB + 1 sparse file.
struct Planted {
  fs::path dir, fifo, folder, big;
  explicit Planted(const std::string& name) : dir(testing::cli_temp_file(name)) {
    fs::remove_all(dir);
    fs::create_directories(dir / "folder.json");
    fifo = dir / "fifo.json";
    folder = dir / "folder.json";
    big = dir / "big.json";
    EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const int fd = ::open(big.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    EXPECT_GE(fd, 0);
    EXPECT_EQ(::ftruncate(fd, static_cast<off_t>(kGiB) + 1), 0);  // sparse: no disk spent
    ::close(fd);
  }
  ~Planted() { fs::remove_all(dir); }
};

// Each command that reads an input, with that input replaced by PATH, its key and kind.
struct Reader {
  const char* command;  // PATH stands for the input
  const char* key;
  const char* limit;  // "a scene file is at most 1 MiB"
};
const Reader kReaders[] = {
    {"trajectory PATH --integrator rk4 --h 0.1 --out OUT", "scene", "a scene file is at most 1 MiB"},
    {"landscape PATH --grid 3,3", "scene", "a scene file is at most 1 MiB"},
    {"list --tableau PATH", "tableau", "a tableau file is at most 1 MiB"},
    {"score plane PATH", "trajectory", "a trajectory is at most 256 MiB"},
    {"merge PATH --out OUT", "report", "a report is at most 1 GiB"},
    {"score --peers PATH --out OUT", "peers", "a peer file is at most 64 MiB"},
};

std::string with_path(std::string command, const fs::path& path) {
  command.replace(command.find("PATH"), 4, path.string());
  if (const auto at = command.find("OUT"); at != std::string::npos)
    command.replace(at, 3, testing::cli_temp_file("bounded-out").string());
  return command;
}

TEST(BoundedReads, ADeviceAFifoOrAFolderIsRefusedAtOnceOnEveryCommand) {
  const Planted p("bounded-kinds");
  for (const Reader& r : kReaders)
    for (const auto& [path, kind] : {std::pair<fs::path, std::string>{"/dev/zero", "a character device"},
                                     {p.fifo, "a FIFO"},
                                     {p.folder, "a folder"}}) {
      SCOPED_TRACE(with_path(r.command, path));
      const auto start = std::chrono::steady_clock::now();
      const CliOutcome o = bounded_rollbench(with_path(r.command, path));
      EXPECT_EQ(o.code, 2) << o.err;
      EXPECT_EQ(o.err, "rollbench: '" + std::string(r.key) + "': '" + path.string() + "' is " + kind + kRegular);
      EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
    }
}

TEST(BoundedReads, AFileOverItsKindsLimitIsRefusedBeforeItIsRead) {
  const Planted p("bounded-size");
  for (const Reader& r : kReaders) {
    SCOPED_TRACE(r.command);
    const auto start = std::chrono::steady_clock::now();
    const CliOutcome o = bounded_rollbench(with_path(r.command, p.big));
    EXPECT_EQ(o.code, 2) << o.err;
    EXPECT_EQ(o.err, "rollbench: '" + std::string(r.key) + "': '" + p.big.string() + "' is 1.07 GB; " + r.limit + "\n");
    // read, 1 GiB takes seconds and a GiB of memory
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  }
}

// A peer file with one solve on scene.
nlohmann::json peer_file_on(const std::string& scene) {
  nlohmann::json run = {
      {"scene", scene},    {"integrator", "peer"}, {"family", "peer"}, {"declared_order", 5}, {"needs_jacobian", false},
      {"rtol", 1e-6},      {"atol", 1e-6},         {"status", "ok"},   {"message", ""},       {"trajectory", "t.csv"},
      {"wall_s", {0.001}}, {"steps", 1},           {"rhs_evals", 1},   {"jacobian_evals", 0}, {"validity_checks", 0}};
  return {{"schema", "rollbench.peers/1"}, {"peer", "test"}, {"t_end", 2.0}, {"dt_out", nullptr}, {"runs", {run}}};
}

TEST(BoundedReads, APeerFilesScenePathIsReadAsAnyScene) {
  const Planted p("bounded-peer");
  const fs::path peers = p.dir / "peers.json";
  const auto refusal = [&](const std::string& scene) {
    std::ofstream(peers) << peer_file_on(scene).dump();
    const CliOutcome o = bounded_rollbench("score --peers " + peers.string() + " --out " + (p.dir / "o.json").string());
    EXPECT_EQ(o.code, 2) << o.err;
    return o.err;
  };
  EXPECT_EQ(refusal("/dev/zero"),
            "rollbench: 'scenes': in /dev/zero: 'scene': '/dev/zero' is a character device" + kRegular);
  EXPECT_EQ(refusal(p.fifo.string()),
            "rollbench: 'scenes': in " + p.fifo.string() + ": 'scene': '" + p.fifo.string() + "' is a FIFO" + kRegular);
  // a JSON file that is no scene: its key shown as a short excerpt, never whole
  const fs::path secret = p.dir / "secret.json";
  std::ofstream(secret) << R"({"secret_api_key_0123456789abcdef0123456789abcdef_TOPSECRET": 1})";
  const std::string err = refusal(secret.string());
  EXPECT_EQ(err.find("TOPSECRET"), std::string::npos) << err;
  EXPECT_NE(err.find("'secret_api_key_0123456789abcdef012345678...': unknown key"), std::string::npos) << err;
}

TEST(BoundedReads, ATableauNestedDeepAsItsNameIsRefusedBeforeParsing) {
  // d44d9b5..e4d8eb6: SIGSEGV in read_tableau's doc["name"].dump()
  const fs::path file = testing::cli_temp_file("deep-name.json");
  std::ofstream(file) << R"({"name": )" << std::string(100000, '[') << std::string(100000, ']') << "}";
  const CliOutcome o = bounded_rollbench("list --tableau " + file.string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_EQ(o.err, "rollbench: tableau file '" + file.string() + "': nests deeper than 64 levels (at byte 73)\n");
  // a name of the wrong type is named by its type, a long one cut to an excerpt
  const auto error_of = [](const std::string& name) -> std::string {
    try {
      parse_tableau_file(R"({"name": )" + name + R"(, "c": [0], "A": [[0]], "b": [1]})", "t.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string rule =
      "tableau file 't.json': 'name': must be a string of 1 to 40 letters, digits, '-', '_' or "
      "'.' (it names rk-<name>), not ";
  EXPECT_EQ(error_of("[[[1]]]"), rule + "an array");
  EXPECT_EQ(error_of("\"" + std::string(100, 'a') + "\""), rule + "\"" + std::string(40, 'a') + "...\"");
  EXPECT_EQ(error_of(R"("a\u001b[31m")"), rule + R"("a\x1b[31m")");
}

// A tableau of s stages of zeros (A strictly lower triangular, b = [1, 0, ...]).
std::string zero_tableau(std::size_t s) {
  std::string row = "[0";
  for (std::size_t j = 1; j < s; ++j) row += ",0";
  row += "]";
  std::string a = "[" + row;
  for (std::size_t i = 1; i < s; ++i) a += "," + row;
  a += "]";
  std::string b = "[1" + row.substr(2);
  return R"({"name": "big", "c": )" + row + R"(, "A": )" + a + R"(, "b": )" + b + "}";
}

TEST(BoundedReads, ATableauOfTooManyStagesIsRefusedBeforeItIsBuilt) {
  // e4d8eb6: 2000 stages took 40 s and 485 MB before "1 to 32 stages"
  const std::string text = zero_tableau(2000);
  const auto start = std::chrono::steady_clock::now();
  try {
    parse_tableau_file(text, "t.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "tableau file 't.json': 'c': holds an array of more than 33 entries; a tableau has 1 to 32 stages");
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  // 33 stages parse; the rows are counted before any coefficient is read
  try {
    parse_tableau_file(zero_tableau(33), "t.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "tableau file 't.json': 'A': a tableau needs 1 to 32 stages, got 33");
  }
  // from the command line the 8 MB file is refused by its size first
  const fs::path file = testing::cli_temp_file("stages-2000.json");
  std::ofstream(file) << text;
  const CliOutcome o = bounded_rollbench("list --tableau " + file.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 'tableau': '" + file.string() + "' is 8.01 MB; a tableau file is at most 1 MiB\n");
}

TEST(BoundedReads, ACsvQuotesItsContentOnlyEscaped) {
  const fs::path csv = testing::cli_temp_file("esc.csv");
  std::ofstream(csv) << "t,x\x1b[2J\x1b[31mred,y\n";
  CliOutcome o = bounded_rollbench("score plane " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: '" + csv.string() +
                       "': line 1, column 2 (x): expected column 'x', got 'x\\x1b[2J\\x1b[31mred'\n");
  EXPECT_EQ(o.err.find('\x1b'), std::string::npos);
  // a row's field: escaped and cut
  std::ofstream(csv) << "t,x,y,cx,cy,cz,wx,wy,wz,r00,r01,r02,r10,r11,r12,r20,r21,r22,energy,normal_force,spin,"
                        "rotation_defect\n0.25,\x1b]0;pwned\x07"
                     << std::string(100, 'z') << ",0,0,0,0,0,0,0,1,0,0,0,1,0,0,0,1,0,0,0,0\n";
  o = bounded_rollbench("score plane " + csv.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: '" + csv.string() + "': line 2, column 2 (x): '\\x1b]0;pwned\\x07" +
                       std::string(30, 'z') + "...' is not a number\n");
  // a line longer than any row
  std::ofstream(csv) << std::string(70000, '0') << "\n";
  o = bounded_rollbench("score plane " + csv.string());
  EXPECT_EQ(o.err, "rollbench: '" + csv.string() +
                       "': line 1: the line is 70000 bytes long; a trajectory's line is at most 65536\n");
}

TEST(BoundedReads, ExcerptsEscapeControlBytesAndNonAsciiAndCut) {
  EXPECT_EQ(escaped_excerpt(std::string("a\x1b\0\n\xff'\\b", 8)), "a\\x1b\\x00\\x0a\\xff\\x27\\x5cb");
  EXPECT_EQ(escaped_excerpt(std::string(41, 'k')), std::string(40, 'k') + "...");
  EXPECT_EQ(escaped_excerpt(std::string(40, 'k')), std::string(40, 'k'));
  // nlohmann's "last read" is the file's text: cut, its "expected" kept
  EXPECT_EQ(json_error_text("[json.exception.parse_error.101] parse error at line 1, column 50: syntax error while "
                            "parsing value - invalid literal; last read: '" +
                            std::string(50, 's') + "'"),
            "parse error at line 1, column 50: syntax error while parsing value - invalid literal; last read: '" +
                std::string(40, 's') + "...'");
  EXPECT_EQ(json_error_text("x - invalid literal; last read: 'ab'; expected end of input"),
            "x - invalid literal; last read: 'ab'; expected end of input");
  EXPECT_EQ(size_in_words(812), "812 bytes");
  EXPECT_EQ(size_in_words(kGiB + 1), "1.07 GB");
  EXPECT_EQ(size_in_words(999999), "1 MB");
  EXPECT_EQ(limit_in_words(256 * kMiB), "256 MiB");
  EXPECT_EQ(limit_in_words(reference_cache_input(9).max_bytes), "82 KiB");
}

TEST(BoundedReads, AFileThatGrowsWhileItIsReadStopsAtItsLimit) {
  // /proc files say 0 bytes and hold more: read up to the limit and one byte, no more
  try {
    read_input_file("/proc/self/maps", InputKind{"test input", 16}, "key");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "'key': '/proc/self/maps' grew past 16 bytes while it was read; a test input is at most 16 bytes");
  }
  const fs::path file = testing::cli_temp_file("sixteen.txt");
  std::ofstream(file) << std::string(16, 'x');
  EXPECT_EQ(read_input_file(file.string(), InputKind{"test input", 16}, "key"), std::string(16, 'x'));
}

}  // namespace
}  // namespace rb

// Numbers from text read strictly, and the caps on them (issue 57, "strict
// numbers and caps"; docs/bad-input.md): a whole number is the whole text in
// its stated range (sscanf took --shard 0/4294967297 as 0/1 and 0/1junk as
// 0/1), --jobs is capped at the cores and refused above 1024 (100000 threads
// aborted the sweep), a thread the system refuses is no abort, a scene's
// t_end is a normal number from 1e-6 to 1e7 (1e-323 aborted fuzz_run), and
// one sweep takes one scene per name.
#include <sys/resource.h>

#include <atomic>
#include <nlohmann/json.hpp>
#include <thread>

#include "bench/lib/run_on_threads.hpp"
#include "bench/lib/sweep.hpp"
#include "problems/whole_number.hpp"
#include "tests/robustness/helpers.hpp"

namespace rb::robustness {
namespace {

std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(StrictNumbers, AWholeNumberIsTheWholeTextInItsRange) {
  EXPECT_EQ(whole_number_in("0", 0, 10), 0);
  EXPECT_EQ(whole_number_in("10", 0, 10), 10);
  EXPECT_EQ(whole_number_in("-60", -60, 60), -60);
  EXPECT_EQ(whole_number_in("007", 0, 10), 7);
  for (const char* bad : {"", "11", "-1", "+1", " 1", "1 ", "1junk", "0x1", "1e1", "1.0", "-", "99999999999999999999"})
    EXPECT_EQ(whole_number_in(bad, 0, 10), std::nullopt) << bad;
  EXPECT_EQ(input_error([] { parse_whole_number("100000", 1, 1024, "jobs"); }),
            "'jobs': '100000' is not a whole number from 1 to 1024");
  // quoted as an escaped excerpt, never raw
  EXPECT_EQ(input_error([] { parse_whole_number("1\x1b[2J", 0, 9, "repeats"); }),
            "'repeats': '1\\x1b[2J' is not a whole number from 0 to 9");
}

TEST(StrictNumbers, AShardIsINWithIBelowNAndNAtMost100000) {
  EXPECT_EQ(parse_shard("0/1"), (std::pair{0, 1}));
  EXPECT_EQ(parse_shard("99999/100000"), (std::pair{99999, 100000}));
  for (const char* bad : {"0/4294967297", "0/1junk", "1/1", "3/2", "-1/2", "0/0", "0/100001", "0/+2", " 0/2", "0/",
                          "/2", "0", "0//2", "0/2/3"})
    EXPECT_EQ(input_error([&] { parse_shard(bad); }),
              "'shard': '" + std::string(bad) + "' is not I/N with 0 <= I < N <= 100000")
        << bad;
}

// The command line: exit status 2 and the message, before any reference.
TEST(StrictNumbers, RunRefusesLooseIntegerOptions) {
  const std::string run = "run --scenes plane --integrators rk4 --out " + temp_path("strict.json").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --shard 0/4294967297", "rollbench: 'shard': '0/4294967297' is not I/N with 0 <= I < N <= 100000\n"},
      {" --shard 0/1junk", "rollbench: 'shard': '0/1junk' is not I/N with 0 <= I < N <= 100000\n"},
      {" --shard 3/2", "rollbench: 'shard': '3/2' is not I/N with 0 <= I < N <= 100000\n"},
      {" --jobs 100000", "rollbench: 'jobs': '100000' is not a whole number from 1 to 1024\n"},
      {" --jobs 0", "rollbench: 'jobs': '0' is not a whole number from 1 to 1024\n"},
      {" --jobs 0x10", "rollbench: 'jobs': '0x10' is not a whole number from 1 to 1024\n"},
      {" --jobs 4294967298", "rollbench: 'jobs': '4294967298' is not a whole number from 1 to 1024\n"},
      {" --repeats -1", "rollbench: 'repeats': '-1' is not a whole number from 0 to 1000\n"},
      {" --repeats 2.5", "rollbench: 'repeats': '2.5' is not a whole number from 0 to 1000\n"},
      {" --repeats 1001", "rollbench: 'repeats': '1001' is not a whole number from 0 to 1000\n"},
      {" --h 2^+3..2^-2", "rollbench: 'h': expected a range like 2^-3..2^-8, got '2^+3..2^-2'\n"},
      {" --h 2^-2..2^-4294967297", "rollbench: 'h': expected a range like 2^-3..2^-8, got '2^-2..2^-4294967297'\n"},
  };
  for (const auto& [option, err] : cases) {
    const CliOutcome o = rollbench(run + option);
    EXPECT_EQ(o.code, 2) << option;
    EXPECT_EQ(o.err, err) << option;
  }
}

// More jobs than cores run on one thread per core, said on standard error;
// the report keeps the jobs asked for (shards on machines of two sizes merge).
TEST(StrictNumbers, JobsAboveTheCoresAreCappedWithANote) {
  const unsigned cores = std::thread::hardware_concurrency();
  if (cores == 0 || cores >= 1024) GTEST_SKIP() << "the machine does not say its cores, or has 1024";
  const auto report = temp_path("jobs-capped.json");
  const CliOutcome o =
      rollbench("run --scenes plane --integrators rk4 --h 0.25 --repeats 0 --jobs 1024 --out " + report.string());
  ASSERT_EQ(o.code, 0) << o.err;
  const std::string c = std::to_string(cores);
  EXPECT_NE(o.err.find("rollbench: note: --jobs 1024 is more than the " + c + " cores here: the runs use " + c +
                       " threads\n"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(report)).at("options").at("jobs"), 1024);
  EXPECT_EQ(threads_for(1024), static_cast<int>(cores));
  EXPECT_EQ(threads_for(0), 1);
}

// Threads the system refuses (here: an address-space limit that leaves no
// room for a thread's stack) are no abort: run_on_threads goes on with the
// threads it has, on this thread when it has none, and every run is done.
// It used to throw std::system_error, or abort (std::terminate) when a
// later thread failed with earlier ones joinable.
// (Not under AddressSanitizer: its own allocations under the limit end the
// process by design.)
TEST(StrictNumbers, ThreadsTheSystemRefusesAreNoAbort) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer dies where an allocation fails";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  GTEST_SKIP() << "AddressSanitizer dies where an allocation fails";
#endif
#endif
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    const rlim_t now = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE));
    const rlimit limit{now + (1 << 20), now + (1 << 20)};  // 1 MiB more: no 8 MiB stack fits
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(4);
    std::atomic<int> ran{0};
    try {
      run_on_threads(
          200, 64, [](std::size_t) { return false; }, [&](std::size_t) { ++ran; }, [](std::size_t) {});
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(ran == 200 ? 0 : 5);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: an exception, 4: no limit set, 5: runs missing";
}

// A scene's t_end is a normal number from 1e-6 to 1e7: 1e-323 (subnormal)
// made fuzz_run's step 0 and the harness abort; it is in the corpus.
TEST(StrictNumbers, ASceneTEndIsANormalNumberWithinItsBounds) {
  const std::string corpus = std::string(RB_SOURCE_DIR) + "/fuzz/corpus/fuzz_run/regress-subnormal-t-end.json";
  EXPECT_EQ(input_error([&] { load_scene(corpus); }),
            "'t_end': t_end must be from 1e-6 to 1e7 (seconds), not 9.881312917e-324");
  EXPECT_EQ(slurp(corpus), slurp(std::string(RB_SOURCE_DIR) + "/fuzz/corpus/fuzz_scene/err-subnormal-t-end.json"));
  for (const char* t : {"1e-323", "5e-324", "2.2e-308", "9.9e-7", "1.0000001e7", "1e300"}) {
    const InputError e = scene_error(replaced(base_scene_text(), R"("t_end": 1.0)", R"("t_end": )" + std::string(t)));
    EXPECT_EQ(e.key(), "t_end") << t;
    EXPECT_EQ(e.message().rfind("t_end must be from 1e-6 to 1e7 (seconds), not ", 0), 0u) << e.message();
  }
  for (const char* t : {"1e-6", "1e7", "15.0"})
    EXPECT_EQ(parse_scene(replaced(base_scene_text(), R"("t_end": 1.0)", R"("t_end": )" + std::string(t))).t_end,
              std::stod(t));
  // every shipped scene is within the bounds
  for (const std::string& name : shipped_scene_names()) {
    const double t_end = load_scene(name).t_end;
    EXPECT_TRUE(t_end >= kMinTEnd && t_end <= kMaxTEnd) << name;
  }
  // on the command line: exit 2, the file's error, no run
  const CliOutcome o =
      rollbench("trajectory " + corpus + " --integrator rk4 --h 0.01 --out " + temp_path("tiny.csv").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "rollbench: 't_end': t_end must be from 1e-6 to 1e7 (seconds), not 9.881312917e-324\n");
  const CliOutcome r = rollbench("run --scenes plane --integrators rk4 --h 0.25 --t-end 1e-323 --out " +
                                 temp_path("tiny.json").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rollbench: 't-end': the end time must be from 1e-6 to 1e7 (seconds), as a scene's t_end\n");
}

// One sweep, one scene per name: the report keys references, runs and fits
// by it, so two scenes named "plane" went into one report unnoticed.
TEST(StrictNumbers, TwoScenesOfOneNameAreRefused) {
  const std::string shipped = slurp(std::string(RB_SCENE_DIR) + "/plane.json");
  const auto other = temp_path("other-plane.json"), copy = temp_path("copy-plane.json");
  std::ofstream(other) << replaced(base_scene_text(), R"("name": "base")", R"("name": "plane")");
  std::ofstream(copy) << shipped;
  const std::string run = "run --integrators rk4 --h 0.25 --out " + temp_path("names.json").string() + " --scenes ";
  CliOutcome o = rollbench(run + "plane," + other.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(
      o.err.find("rollbench: 'scenes': 'plane' and '" + other.string() + "' are two different scenes named 'plane'\n"),
      std::string::npos)
      << o.err;
  EXPECT_EQ(o.err.find("reference of"), std::string::npos) << o.err;
  o = rollbench(run + other.string() + "," + copy.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("rollbench: 'scenes': '" + other.string() + "' and '" + copy.string() +
                       "' are two different scenes named 'plane'\n"),
            std::string::npos)
      << o.err;
  o = rollbench(run + "plane," + copy.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("rollbench: 'scenes': scene 'plane' is given twice ('plane' and '" + copy.string() + "')\n"),
            std::string::npos)
      << o.err;
  // a file named like a scene of the preset's stability study (or horizon
  // study): the study's records would carry the name of another scene
  const auto bumpy = temp_path("bumpy-long.json");
  std::ofstream(bumpy) << replaced(base_scene_text(), R"("name": "base")", R"("name": "bumpy-long")");
  o = rollbench("run --preset default --integrators rk4 --no-horizon --out " + temp_path("study.json").string() +
                " --scenes " + bumpy.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("rollbench: 'scenes': '" + bumpy.string() +
                       "' and 'bumpy-long' are two different scenes named 'bumpy-long'\n"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(o.err.find("reference of"), std::string::npos) << o.err;
  // the library call the sweep and score --peers make
  SweepSpec spec = preset("quick");
  spec.scenes = {"plane", other.string()};
  EXPECT_EQ(input_error([&] { prepare_scenes(spec, false); }),
            "'scenes': 'plane' and '" + other.string() + "' are two different scenes named 'plane'");
  // a study may run a scene of the sweep again, by another path
  spec.scenes = {copy.string()};
  spec.stability.enabled = true;
  spec.stability.scenes = {"plane"};
  EXPECT_EQ(input_error([&] { prepare_scenes(spec, true); }), "(accepted)");
  spec.scenes = {other.string()};
  EXPECT_EQ(input_error([&] { prepare_scenes(spec, true); }),
            "'scenes': '" + other.string() + "' and 'plane' are two different scenes named 'plane'");
}

}  // namespace
}  // namespace rb::robustness

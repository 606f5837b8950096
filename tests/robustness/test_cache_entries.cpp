// issue 32: a cached reference is verified, never trusted. Entries planted in
// a shared --cache (zeroed, short, forged with a right checksum) are refused
// with a note and recomputed; the run's errors stay those of a fresh reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/lib/reference.hpp"
#include "problems/input_file.hpp"
#include "tests/cli_run.hpp"

namespace rb {
namespace {

namespace fs = std::filesystem;
using testing::cli_temp_file;
using testing::run_rollbench;
using testing::slurp;

struct CachedRun {
  testing::CliOutcome outcome;
  nlohmann::json report;
};

CachedRun run_with_cache(const fs::path& cache, const std::string& tag) {
  const fs::path out = cli_temp_file("cache-" + tag + ".json");
  CachedRun r;
  r.outcome = run_rollbench(
      "run --scenes valley-sideways --integrators rk4 --h 2^-3..2^-4 --no-stability --repeats 1 "
      "--no-horizon --cache " +
      cache.string() + " --out " + out.string());
  if (r.outcome.code == 0) r.report = nlohmann::json::parse(slurp(out));
  fs::remove(out);
  return r;
}

fs::path the_entry(const fs::path& cache) {
  fs::path found;
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().filename().string().rfind("reference-", 0) == 0) found = e.path();
  return found;
}

double first_error(const nlohmann::json& report) { return report.at("runs").at(0).at("error").at("contact"); }

// Rewrites the entry's points by `change`; `reseal` gives it a right checksum, as a forger would.
template <class Change>
void plant(const fs::path& entry, Change change, bool reseal) {
  nlohmann::json j = nlohmann::json::parse(slurp(entry));
  change(j["reference"]["points"]);
  if (reseal) j["checksum"] = cache_entry_checksum(j);
  std::ofstream(entry) << j.dump();
}

void zero_every_point(nlohmann::json& points) {
  for (auto& row : points)
    for (auto& v : row) v = 0.0;
}

class CacheEntries : public ::testing::Test {
 protected:
  void SetUp() override {
    cache = cli_temp_file("cache-dir");
    fs::remove_all(cache);
    fs::create_directories(cache);
    fresh = run_with_cache(cache, "fresh");
    ASSERT_EQ(fresh.outcome.code, 0) << fresh.outcome.err;
    entry = the_entry(cache);
    ASSERT_FALSE(entry.empty()) << "no cache entry was written";
  }
  void TearDown() override { fs::remove_all(cache); }

  // the planted entry is refused for `why`, recomputed, and the errors are the fresh run's
  void expect_refused(const std::string& why) {
    const CachedRun again = run_with_cache(cache, "again");
    ASSERT_EQ(again.outcome.code, 0) << again.outcome.err;
    EXPECT_NE(again.outcome.err.find("rollbench: note: the cached reference '" + entry.string() +
                                     "' of scene valley-sideways is not used (" + why + "); recomputing"),
              std::string::npos)
        << again.outcome.err;
    EXPECT_EQ(first_error(again.report), first_error(fresh.report));
    const CachedRun third = run_with_cache(cache, "third");  // the recomputed entry replaced the planted one
    EXPECT_EQ(third.outcome.err.find("is not used"), std::string::npos) << third.outcome.err;
    EXPECT_EQ(first_error(third.report), first_error(fresh.report));
  }

  fs::path cache, entry;
  CachedRun fresh;
};

TEST_F(CacheEntries, AnIntactEntryIsUsed) {
  const CachedRun again = run_with_cache(cache, "again");
  EXPECT_EQ(again.outcome.err.find("is not used"), std::string::npos) << again.outcome.err;
  EXPECT_EQ(first_error(again.report), first_error(fresh.report));
}

TEST_F(CacheEntries, AZeroedEntryIsRecomputed) {
  plant(entry, zero_every_point, false);
  expect_refused("checksum differs");
}

TEST_F(CacheEntries, AZeroedEntryWithARightChecksumIsRecomputed) {
  plant(entry, zero_every_point, true);
  expect_refused("a point whose R is not a rotation");
}

TEST_F(CacheEntries, AShortEntryIsRecomputed) {
  std::size_t kept = 0;
  plant(
      entry,
      [&](nlohmann::json& points) {
        points.erase(points.size() - 1);
        kept = points.size();
      },
      true);
  expect_refused("holds " + std::to_string(kept) + " points for " + std::to_string(kept + 1) + " output times");
}

TEST_F(CacheEntries, AnEntryWithoutItsErrorPerComponentIsRecomputed) {
  // the order fits' floors: an entry older than them is not read
  nlohmann::json j = nlohmann::json::parse(slurp(entry));
  j["reference"].erase("component_errors");
  j["checksum"] = cache_entry_checksum(j);
  std::ofstream(entry) << j.dump();
  expect_refused("no own error per component");
}

TEST_F(CacheEntries, TheReferenceStatesItsOwnErrorPerComponent) {
  // each component's disagreement, the largest of them the overall error
  const nlohmann::json& ref = fresh.report.at("references").at(0);
  double largest = 0.0;
  for (const char* c : {"contact", "centre", "omega", "rotation"}) {
    const double e = ref.at("component_errors").at(c).get<double>();
    EXPECT_GE(e, 0.0) << c;
    EXPECT_LE(e, ref.at("error").get<double>()) << c;
    largest = std::max(largest, e);
  }
  EXPECT_DOUBLE_EQ(largest, ref.at("error").get<double>());
}

TEST_F(CacheEntries, AGibEntryIsRecomputedWithoutBeingRead) {
  // e4d8eb6 read a 1 GiB sparse entry whole (1.07 GB, 18 s): its size is checked first, against its grid's
  const std::size_t times = nlohmann::json::parse(slurp(entry)).at("made_from").at("times").size();
  fs::resize_file(entry, kGiB);  // sparse: no disk spent
  expect_refused("'" + entry.string() + "' is 1.07 GB; a cached reference is at most " +
                 limit_in_words(reference_cache_input(times).max_bytes));
}

}  // namespace
}  // namespace rb

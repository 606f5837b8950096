// Merging shard reports needs every shard of the sweep exactly once; what is
// missing or repeated is named, so that only that shard has to run again
// (scripts/slurm/ relies on this; tests/slurm runs it on a real scheduler).
#include <gtest/gtest.h>

#include "bench/lib/report.hpp"
#include "problems/input_error.hpp"

namespace rb {
namespace {

using json = nlohmann::json;

// The parts of a shard report that merging reads, with no runs in them.
json empty_shard(long index, long count) {
  return {{"schema", kReportSchema},
          {"options", {{"preset", "quick"}, {"shard", {index, count}}}},
          {"references", json::array()},
          {"runs", json::array()},
          {"stability", {{"drift", json::array()}, {"largest_stable_h", json::array()}}}};
}

std::string merge_error(const std::vector<json>& shards) {
  try {
    merge_reports(shards);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(merged)";
}

TEST(MergeShards, EveryShardOnceMerges) {
  const json merged = merge_reports({empty_shard(2, 3), empty_shard(0, 3), empty_shard(1, 3)});
  EXPECT_EQ(merged.at("options").at("shard"), json({0, 1}));
}

TEST(MergeShards, MissingShardsAreNamed) {
  EXPECT_EQ(merge_error({empty_shard(0, 3), empty_shard(2, 3)}), "'reports': shard 1 of 3 is missing (given: 0, 2)");
  EXPECT_EQ(merge_error({empty_shard(3, 4), empty_shard(1, 4)}),
            "'reports': shards 0, 2 of 4 are missing (given: 1, 3)");
}

TEST(MergeShards, RepeatedOrMixedShardsAreRefused) {
  EXPECT_EQ(merge_error({empty_shard(0, 2), empty_shard(0, 2), empty_shard(1, 2)}),
            "'reports': shard 0 of 2 is given twice");
  EXPECT_EQ(merge_error({empty_shard(0, 2), empty_shard(1, 3)}),
            "'reports': the reports come from sweeps cut into 2 and 3 shards");
}

}  // namespace
}  // namespace rb

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

// A shard's runs are parsed into what the fits read: a run a fit cannot
// read is refused with the shard's file and the key, not a JSON exception.
TEST(MergeShards, ARunTheFitsCannotReadNamesItsFileAndKey) {
  const json run = {{"index", 0},
                    {"scene", "plane"},
                    {"integrator", "rk4"},
                    {"adaptive", false},
                    {"declared_order", 4},
                    {"declared_rotation_order", 4},
                    {"h", 0.5},
                    {"rtol", nullptr},
                    {"stop_time", 1.0},
                    {"status", "ok"},
                    {"steps", 2},
                    {"final",
                     {{"t", 1.0},
                      {"contact", {0.0, 0.0}},
                      {"centre", {0.0, 0.0, 0.1}},
                      {"omega", {0.0, 0.0, nullptr}},
                      {"R", {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}}},
                    {"error",
                     {{"contact", 1e-3},
                      {"centre", 1e-3},
                      {"omega", nullptr},
                      {"rotation", 1e-4},
                      {"worst", 1e-3},
                      {"below_floor", {"omega"}}}}};
  auto merged_with = [&](const json& bad) -> std::string {
    json second = empty_shard(1, 2);
    second["runs"] = json::array({bad});  // {bad} alone is a copy of bad under clang, an array under GCC
    try {
      merge_reports({empty_shard(0, 2), second}, {"a.json", "b.json"});
    } catch (const InputError& e) {
      return e.what();
    }
    return "(merged)";
  };
  EXPECT_EQ(merged_with(run), "(merged)");
  json no_omega = run;
  no_omega["error"].erase("omega");
  EXPECT_EQ(merged_with(no_omega), "'reports': the report 'b.json': runs[0].error.omega is missing");
  json text_h = run;
  text_h["h"] = "0.5";
  EXPECT_EQ(merged_with(text_h), "'reports': the report 'b.json': runs[0].h is not a number or null");
  json no_status = run;
  no_status.erase("status");
  EXPECT_EQ(merged_with(no_status), "'reports': the report 'b.json': runs[0].status is missing");
  json short_centre = run;
  short_centre["final"]["centre"] = {0.0, 0.0};
  EXPECT_EQ(merged_with(short_centre),
            "'reports': the report 'b.json': runs[0].final.centre is not a list of 3 numbers");
  json float_steps = run;
  float_steps["steps"] = 2.5;
  EXPECT_EQ(merged_with(float_steps), "'reports': the report 'b.json': runs[0].steps is not an integer");
  json bad_below = run;
  bad_below["error"]["below_floor"] = {1};
  EXPECT_EQ(merged_with(bad_below),
            "'reports': the report 'b.json': runs[0].error.below_floor holds something that is not a string");
  json no_scene = empty_shard(1, 2);
  no_scene["references"] = {{{"error", 1e-12}}};
  EXPECT_EQ(merge_error({empty_shard(0, 2), no_scene}),
            "'reports': the report 'shard report 1': references[0].scene is missing or not a string");
  json no_scale = empty_shard(1, 2);
  no_scale["references"] = {{{"scene", "bowl"}, {"error", 1e-12}}};
  EXPECT_EQ(merge_error({empty_shard(0, 2), no_scale}),
            "'reports': the report 'shard report 1': references[0].omega_scale is missing or not a number");
  json bad_floor = empty_shard(1, 2);
  bad_floor["references"] = {
      {{"scene", "bowl"}, {"error", 1e-12}, {"omega_scale", 1.0}, {"component_errors", {{"omega", "tiny"}}}}};
  EXPECT_EQ(merge_error({empty_shard(0, 2), bad_floor}),
            "'reports': the report 'shard report 1': references[0].component_errors.omega is not a number or null");
}

// A shard's orders and tolerance fits are fitted again in the merge, but
// what a report holds must read: a wrong one is named by file and key.
TEST(MergeShards, AnOrderOrToleranceFitThatDoesNotReadNamesItsFileAndKey) {
  const json order = orders_json({ReportOrder{"plane", "rk4", 4, 4, {}}}).at(0);
  ToleranceFit tolerance{"plane", "rk45", {}, {}};
  tolerance.line.slope = 1.0;
  const json fit = tolerance_fits_json({tolerance}).at(0);
  const auto merged_with = [](const char* key, const json& entry) {
    json second = empty_shard(1, 2);
    second[key] = json::array({entry});
    return merge_error({empty_shard(0, 2), second});
  };
  EXPECT_EQ(merged_with("orders", order), "(merged)");
  EXPECT_EQ(merged_with("tolerance_fits", fit), "(merged)");
  json text_slope = order;
  text_slope["fits"]["omega"]["slope"] = "2";
  EXPECT_EQ(merged_with("orders", text_slope),
            "'reports': the report 'shard report 1': orders[0].fits.omega.slope is not a number or null");
  json no_self = order;
  no_self["self_convergence"].erase("rotation");
  EXPECT_EQ(merged_with("orders", no_self),
            "'reports': the report 'shard report 1': orders[0].self_convergence.rotation is missing");
  json bad_reason = order;
  bad_reason["inconclusive_reason"]["centre"] = 3;
  EXPECT_EQ(merged_with("orders", bad_reason),
            "'reports': the report 'shard report 1': orders[0].inconclusive_reason.centre is not a string or null");
  json no_points = fit;
  no_points["step_order"].erase("points");
  EXPECT_EQ(merged_with("tolerance_fits", no_points),
            "'reports': the report 'shard report 1': tolerance_fits[0].step_order.points is missing");
  json not_a_list = empty_shard(1, 2);
  not_a_list["orders"] = json::object();
  EXPECT_EQ(merge_error({empty_shard(0, 2), not_a_list}),
            "'reports': the report 'shard report 1': 'orders' is not a list");
}

// The merged report lists the components as a sweep's does.
TEST(MergeShards, TheMergedReportListsTheErrorComponents) {
  const json merged = merge_reports({empty_shard(1, 2), empty_shard(0, 2)});
  EXPECT_EQ(merged.at("error_components"), error_components_json());
  EXPECT_EQ(merged.at("error_components").size(), kErrorComponentCount);
}

// A run entry that merges (the fits read it), at index.
json run_at(const json& index) {
  return {{"index", index},
          {"scene", "plane"},
          {"integrator", "rk4"},
          {"adaptive", false},
          {"declared_order", 4},
          {"declared_rotation_order", 4},
          {"h", 0.5},
          {"rtol", nullptr},
          {"stop_time", 1.0},
          {"status", "ok"},
          {"steps", 2},
          {"final",
           {{"t", 1.0},
            {"contact", {0.0, 0.0}},
            {"centre", {0.0, 0.0, 0.1}},
            {"omega", {0.0, 0.0, 0.0}},
            {"R", {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}}},
          {"error",
           {{"contact", 1e-3},
            {"centre", 1e-3},
            {"omega", 1e-3},
            {"rotation", 1e-4},
            {"worst", 1e-3},
            {"below_floor", json::array()}}}};
}

json shard_with_runs(long index, long count, const std::vector<json>& indices) {
  json shard = empty_shard(index, count);
  for (const json& i : indices) shard["runs"].push_back(run_at(i));
  return shard;
}

std::string merge_error(const std::vector<json>& shards, const std::vector<std::string>& files) {
  try {
    merge_reports(shards, files);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(merged)";
}

// Each run index once across the shards, from 0 to the number of runs - 1
// (issue 57: two shards with the same runs merged into runs 0,0,2,2...; -5
// and 2^64 - 1 were taken): what is held twice names both files, whatever
// the two say, and an index out of range names its file and place.
TEST(MergeShards, EachRunIndexOnceAndInRange) {
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0, 2}), shard_with_runs(1, 2, {1, 3})}, {"a.json", "b.json"}),
            "(merged)");
  json contradicting = shard_with_runs(1, 2, {0, 2});
  contradicting["runs"][0]["error"]["worst"] = 123;
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0, 2}), contradicting}, {"a.json", "b.json"}),
            "'reports': run index 0 is in both 'a.json' (runs[0]) and 'b.json' (runs[0]): each is in one shard only");
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0, 2}), shard_with_runs(1, 2, {0, 2})}, {"a.json", "b.json"}),
            "'reports': run index 0 is in both 'a.json' (runs[0]) and 'b.json' (runs[0]): each is in one shard only");
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0, 1}), shard_with_runs(1, 2, {2, 1})}, {"a.json", "b.json"}),
            "'reports': run index 1 is in both 'a.json' (runs[1]) and 'b.json' (runs[1]): each is in one shard only");
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0}), shard_with_runs(1, 2, {-5})}, {"a.json", "b.json"}),
            "'reports': the report 'b.json': runs[0].index is -5, not a whole number from 0 to 1 (the shards hold 2 "
            "runs, each index once)");
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0}), shard_with_runs(1, 2, {json(18446744073709551615ull)})},
                        {"a.json", "b.json"}),
            "'reports': the report 'b.json': runs[0].index is 18446744073709551615, not a whole number from 0 to 1 "
            "(the shards hold 2 runs, each index once)");
  // a gap is an index beyond the runs the shards hold
  EXPECT_EQ(merge_error({shard_with_runs(0, 2, {0}), shard_with_runs(1, 2, {3})}, {"a.json", "b.json"}),
            "'reports': the report 'b.json': runs[0].index is 3, not a whole number from 0 to 1 (the shards hold 2 "
            "runs, each index once)");
}

// The stability study's records (drift, then the largest-stable-h searches,
// one index space) and the horizon runs are checked the same way.
TEST(MergeShards, EachStabilityAndHorizonIndexOnce) {
  json a = empty_shard(0, 2), b = empty_shard(1, 2);
  a["stability"]["drift"] = {{{"index", 0}}};
  b["stability"]["largest_stable_h"] = {{{"index", 1}}};
  a["horizon"] = {{"runs", {{{"index", 0}}}}};
  b["horizon"] = {{"runs", {{{"index", 1}}}}};
  EXPECT_EQ(merge_error({a, b}, {"a.json", "b.json"}), "(merged)");
  json twice = b;
  twice["stability"]["largest_stable_h"][0]["index"] = 0;
  EXPECT_EQ(merge_error({a, twice}, {"a.json", "b.json"}),
            "'reports': stability record index 0 is in both 'a.json' (stability.drift[0]) and 'b.json' "
            "(stability.largest_stable_h[0]): each is in one shard only");
  json fraction = b;
  fraction["horizon"]["runs"][0]["index"] = 0.5;
  EXPECT_EQ(merge_error({a, fraction}, {"a.json", "b.json"}),
            "'reports': the report 'b.json': horizon.runs[0].index is 0.5, not a whole number from 0 to 1 (the "
            "shards hold 2 horizon runs, each index once)");
}

// One name, one scene: shards whose references of a scene disagree on what
// the scene is were made of two scenes with one name.
TEST(MergeShards, TwoScenesOfOneNameAreRefused) {
  const json reference = {{"scene", "plane"},   {"error", 1e-12},        {"omega_scale", 1.0}, {"t_end", 1.0},
                          {"inertia", nullptr}, {"r_feeds_back", false}, {"kind", "exact"},    {"method", "exact"}};
  json a = empty_shard(0, 2), b = empty_shard(1, 2);
  a["references"] = json::array({reference});
  b["references"] = json::array({reference});
  EXPECT_EQ(merge_error({a, b}, {"a.json", "b.json"}), "(merged)");
  b["references"][0]["t_end"] = 2.0;
  EXPECT_EQ(merge_error({a, b}, {"a.json", "b.json"}),
            "'reports': scene 'plane' differs between 'a.json' and 'b.json' (its reference's t_end: 1.0 and 2.0): "
            "two scenes with one name");
}

}  // namespace
}  // namespace rb

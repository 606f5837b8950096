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

}  // namespace
}  // namespace rb

#pragma once
// The pieces of a report that its files share (bench/lib/report.hpp lists
// the files); not for use outside them.
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bench/lib/stability.hpp"
#include "bench/lib/sweep.hpp"

namespace rb::report_parts {

// NaN is "not measured": null in JSON.
inline nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// null (or anything not a number) reads NaN.
inline double as_number(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : kNaN; }

// The sections a Report carries through as JSON, by their key (null: the
// report has none), for Report or const Report.
template <typename R>
auto carried_sections(R& report) {
  using Section = std::pair<const char*, decltype(&report.schema)>;
  return std::array<Section, 10>{{{"schema", &report.schema},
                                  {"created", &report.created},
                                  {"git", &report.git},
                                  {"machine", &report.machine},
                                  {"build", &report.build},
                                  {"preset", &report.preset},
                                  {"timed_call", &report.timed_call},
                                  {"stability", &report.stability},
                                  {"horizon", &report.horizon},
                                  {"regime", &report.regime}}};
}

// The keys a Report writes from its typed members.
inline constexpr std::array<const char*, 6> kTypedReportKeys = {"options", "references",     "runs",
                                                                "orders",  "tolerance_fits", "error_components"};

// report_provenance.cpp: where and when the report was made, and how.
nlohmann::json machine_json();
nlohmann::json build_json();
std::string utc_now();
nlohmann::json options_json(const SweepSpec& spec);  // without "shard"
nlohmann::json timed_call_json(const SweepSpec& spec);
// The stability study's drift and blow-up bounds, in the options and in each stability record.
nlohmann::json bounds_json(const StabilityBounds& bounds);

// run_json.cpp: a scene's reference entry, and the stability study.
nlohmann::json reference_json(const SweepScene& scene);
nlohmann::json stability_json(const StabilityResults& stability);

}  // namespace rb::report_parts

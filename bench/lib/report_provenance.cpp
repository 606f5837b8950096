// Where and when a report was made, and how: the machine, the build, the
// time, and the sweep's options and timed call as the report states them.
#include <gsl/gsl_version.h>
#include <sys/utsname.h>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <ctime>
#include <fstream>
#include <thread>

#include "bench/lib/horizon.hpp"
#include "bench/lib/report_parts.hpp"
#include "problems/utf8.hpp"

namespace rb::report_parts {

using json = nlohmann::json;

namespace {

std::string first_line_of(const std::string& path, const std::string& prefix) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  return "unknown";
}

}  // namespace

// The stability study's drift and blow-up bounds, as the report states them.
json bounds_json(const StabilityBounds& b) {
  return {{"energy", b.energy_fraction},        {"rotation_defect", b.rotation_defect},
          {"blow_up_energy", b.blow_up_energy}, {"blow_up_defect", b.blow_up_defect},
          {"blow_up_steps", b.blow_up_steps},   {"growth_exponent", b.growth_exponent},
          {"growth_floor", b.growth_floor}};
}

json machine_json() {
  utsname u{};
  uname(&u);
  std::ifstream loadavg("/proc/loadavg");
  double l1 = kNaN, l5 = kNaN, l15 = kNaN;
  loadavg >> l1 >> l5 >> l15;
  return {{"cpu", first_line_of("/proc/cpuinfo", "model name")},
          {"cores", std::thread::hardware_concurrency()},
          {"os", std::string(u.sysname) + " " + u.release + " " + u.machine},
          {"load", {number(l1), number(l5), number(l15)}}};
}

json build_json() {
  return {{"compiler", std::string("g++ ") + __VERSION__},
          {"flags", RB_BUILD_FLAGS},
          {"type", RB_BUILD_TYPE},
          {"preset", RB_BUILD_PRESET},
          {"libraries",
           {{"boost", BOOST_LIB_VERSION},
            {"gsl", GSL_VERSION},
            {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                          std::to_string(EIGEN_MINOR_VERSION)},
            {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                                  std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                                  std::to_string(NLOHMANN_JSON_VERSION_PATCH)}}}};
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

json options_json(const SweepSpec& s) {
  const StabilitySpec& st = s.stability;
  // scene paths as the user typed them: any bytes, text here
  std::vector<std::string> scenes;
  for (const std::string& scene : s.scenes) scenes.push_back(valid_utf8(scene));
  return {{"preset", s.preset},
          {"scenes", scenes},
          {"integrators", s.integrators},
          {"h", s.hs},
          {"tol", s.tols},
          {"t_end", number(s.t_end > 0 ? s.t_end : kNaN)},
          {"dt_out", number(s.dt_out > 0 ? s.dt_out : kNaN)},
          {"error_dt", s.error_dt},
          {"repeats", s.repeats},
          {"repeat_budget_s", s.repeat_budget_s},
          {"jobs", s.jobs},
          {"max_steps", s.max_steps},
          {"controller", s.controller ? json(s.controller->name) : json(nullptr)},
          {"stability",
           {{"enabled", st.enabled},
            {"scenes", st.scenes},
            {"integrators", st.integrators},
            {"drift_h", st.drift_h},
            {"drift_t_end", st.drift_t_end},
            {"search_h_max", st.search_h_max},
            {"search_h_min", st.search_h_min},
            {"horizons", st.horizons},
            // the key of before (one horizon): the last, which every rung runs to
            {"search_t_end", number(st.horizons.empty() ? kNaN : st.horizons.back())},
            {"search_outputs", st.search_outputs},
            {"bounds", bounds_json(st.bounds)}}},
          {"horizon", horizon_options_json(s.horizon)}};
}

// What each timed call contains, the same for every method.
json timed_call_json(const SweepSpec& spec) {
  const std::string outputs = spec.dt_out > 0.0
                                  ? "every multiple of dt_out up to t_end (for a fixed-step method, those "
                                    "that are multiples of h)"
                                  : "t_end only";
  return {
      {"outputs", outputs},
      {"contains",
       "one integrate() call from t = 0 to t_end recording the outputs above: every step with its rhs "
       "evaluations, the model's validity check of the start and of each accepted state (validity_checks), "
       "the finiteness and domain check of each recorded output, and copying the recorded states; not the untimed "
       "warm-up call before it, not the error measurement; "
       "for a --stepper plug-in run in its own process, the time the child measured around the integration after an "
       "untimed warm-up run in it (not the fork, the pipe or the warm-up)"},
      {"error_max",
       "the largest error over the timed run's steps: from an untimed run recording every multiple "
       "of error_dt (dt_out when given) up to t_end where that run takes the timed run's steps "
       "(fixed-step and dense-output methods), else over the timed run's own outputs; then "
       "error_max_run.same_steps is false and error_grid holds the grid run's errors"}};
}

}  // namespace rb::report_parts

#include "bench/lib/stability.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "bench/lib/drift.hpp"
#include "bench/lib/integrate_safely.hpp"
#include "integrators/registry.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

bool mine(const SweepSpec& spec, std::size_t index) {
  return static_cast<int>(index % static_cast<std::size_t>(spec.shard_count)) == spec.shard_index;
}

std::vector<double> log_spaced(double from, double to, int count) {
  std::vector<double> t;
  for (int k = 0; k < count; ++k) {
    const double v = from * std::pow(to / from, static_cast<double>(k) / (count - 1));
    if (t.empty() || v > t.back()) t.push_back(k + 1 == count ? to : v);
  }
  return t;
}

DriftRecord drift_run(const Problem& problem, const Integrator& m, const StabilitySpec& st) {
  DriftRecord d;
  d.scene = problem.name();
  d.method = m.info();
  d.h = st.drift_h;
  RunOptions o;
  o.t_end = st.drift_t_end;
  o.h = st.drift_h;
  o.rtol = o.atol = 1e-8;  // used by adaptive methods only
  o.output_times = log_spaced(10.0 * st.drift_h, st.drift_t_end, st.drift_samples);
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult run = integrate_safely(m, problem, o);
  d.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  d.status = run.status;
  d.message = run.message;
  d.stop_time = run.stop_time;
  d.cost = run.cost;
  const DriftMeter meter(problem);
  for (std::size_t i = 0; i < run.output.t.size(); ++i) {
    const Drift x = meter.at(run.output.y[i]);
    d.t.push_back(run.output.t[i]);
    d.energy_error.push_back(x.energy);
    d.rotation_defect.push_back(x.rotation_defect);
  }
  return d;
}

StableStepRecord stable_step_search(const SweepScene& s, const Integrator& m, const StabilitySpec& st) {
  StableStepRecord r;
  r.scene = s.scene.name;
  r.method = m.info();
  r.energy_scale = energy_scale(s.problem);
  r.energy_fraction = st.energy_fraction;
  r.rotation_defect_bound = st.rotation_defect_bound;
  const DriftMeter meter(s.problem);
  // upward from the smallest step, so that every h below the answer is tried
  for (double h = st.search_h_min; h <= st.search_h_max * (1 + 1e-12); h *= 2) {
    const RunRecord run = run_task(s, SweepTask{0, 0, m.name(), h, kNaN, {}}, 5'000'000);
    // both over the run: the recorded states (every multiple of h on the
    // error grid) and the last one
    const Drift last = meter.at(run.final_state);
    StableStepTry t{h, run.status, kNaN, std::max(run.rotation_drift, last.rotation_defect), false};
    if (run.status == Status::ok) t.energy_error = std::max(run.energy_drift, last.energy) / r.energy_scale;
    t.stable = run.status == Status::ok && t.energy_error <= st.energy_fraction &&
               t.rotation_defect < st.rotation_defect_bound;
    r.tried.push_back(t);
    if (!t.stable) break;
    r.h = h;
    r.rotation_defect = t.rotation_defect;
  }
  r.at_limit = !r.tried.empty() && r.tried.back().stable;
  return r;
}

}  // namespace

StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress) {
  StabilityResults out;
  if (!spec.stability.enabled) return out;
  const StabilitySpec& st = spec.stability;

  // the scenes once at the search length; stability needs no reference
  SweepSpec search = spec;
  search.scenes = st.scenes;
  search.t_end = st.search_t_end;
  search.shard_count = 1;
  const std::vector<SweepScene> scenes = prepare_scenes(search, false);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };

  std::size_t index = 0;
  for (const SweepScene& s : scenes)
    for (const std::string& name : st.integrators) {
      if (mine(spec, index)) {
        // the run's own t_end overrides the shortened search length
        DriftRecord d = drift_run(s.problem, find_integrator(name), st);
        d.index = index;
        progress("stability: drift of " + name + " on " + s.scene.name + ": " + std::string(status_name(d.status)) +
                 " (" + progress_line("drift", index + 1, scenes.size() * st.integrators.size(), elapsed()) + ")");
        out.drift.push_back(std::move(d));
      }
      ++index;
    }

  std::vector<std::string> fixed;
  if (spec.integrators.empty()) {
    for (const auto& m : registry())
      if (!m->adaptive()) fixed.push_back(m->name());
  } else {
    for (const std::string& name : spec.integrators)
      if (!find_integrator(name).adaptive()) fixed.push_back(name);
  }
  const auto search_start = elapsed();
  std::size_t searched = 0;
  for (const SweepScene& s : scenes)
    for (const std::string& name : fixed) {
      if (mine(spec, index)) {
        StableStepRecord r = stable_step_search(s, find_integrator(name), st);
        r.index = index;
        out.largest_stable_h.push_back(std::move(r));
      }
      ++index;
      if (++searched % 8 == 0)
        progress(progress_line("stability: largest stable h", searched, scenes.size() * fixed.size(),
                               elapsed() - search_start, "methods x scenes"));
    }
  progress("stability: done");
  return out;
}

}  // namespace rb

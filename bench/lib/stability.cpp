#include "bench/lib/stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "bench/lib/drift.hpp"
#include "bench/lib/integrate_safely.hpp"
#include "integrators/registry.hpp"
#include "problems/utf8.hpp"

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
  o.tolerances = Tolerances(1e-8, 1e-8);  // used by adaptive methods (and GSL's implicit fixed-step Newton) only
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

// One rung: a fixed-step run to the horizon recording about
// search_outputs states at whole steps, judged on them and the last.
StableStepTry stable_step_try(const Problem& problem, const Integrator& m, double h, double energy_scale,
                              const StabilitySpec& st) {
  RunOptions o;
  o.t_end = st.search_t_end;
  o.h = h;
  o.max_steps = 5'000'000;
  const double taken = step_taken(h, st.search_t_end);
  const long steps = std::lround(st.search_t_end / taken);
  const long every = std::max(1L, steps / std::max(1, st.search_outputs));
  for (long n = every; n < steps; n += every) o.output_times.push_back(taken * static_cast<double>(n));
  const RunResult run = integrate_safely(m, problem, o);
  const DriftMeter meter(problem);
  std::vector<double> t, energy, defect;
  const auto record = [&](double at, const FlatState& y) {
    const Drift d = meter.at(y);
    t.push_back(at);
    energy.push_back(d.energy / energy_scale);
    defect.push_back(d.rotation_defect);
  };
  for (std::size_t i = 0; i < run.output.t.size(); ++i)
    if (run.output.t[i] <= run.stop_time) record(run.output.t[i], run.output.y[i]);
  // the last state: the end, or the last valid state of a run that stopped
  if (t.empty() || run.stop_time > t.back()) record(run.stop_time, run.final_state);
  const RungVerdict v = judge_rung(run.status, t, energy, defect, st.search_t_end, st.bounds);
  return {h,
          run.status,
          valid_utf8(run.message),
          run.stop_time,
          v.energy_error,
          v.rotation_defect,
          v.energy_growth,
          v.defect_growth,
          v.failure,
          v.failure == StabilityFailure::none};
}

StableStepRecord stable_step_search(const SweepScene& s, const Integrator& m, const StabilitySpec& st) {
  StableStepRecord r;
  r.scene = s.scene.name;
  r.method = m.info();
  r.horizon = st.search_t_end;
  r.energy_scale = energy_scale(s.problem);
  r.bounds = st.bounds;
  // upward from the smallest step, so that every h below the answer is tried
  for (double h = st.search_h_min; h <= st.search_h_max * (1 + 1e-12); h *= 2) {
    r.tried.push_back(stable_step_try(s.problem, m, h, r.energy_scale, st));
    const StableStepTry& t = r.tried.back();
    if (!t.stable) break;
    r.h = h;
    r.energy_error = t.energy_error;
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

#include "bench/lib/stability.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

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
  d.integrator = m.name();
  d.family = m.family();
  d.h = st.drift_h;
  RunOptions o;
  o.t_end = st.drift_t_end;
  o.h = st.drift_h;
  o.rtol = o.atol = 1e-8;  // used by adaptive methods only
  o.output_times = log_spaced(10.0 * st.drift_h, st.drift_t_end, st.drift_samples);
  const auto t0 = std::chrono::steady_clock::now();
  RunResult run;
  try {
    run = m.integrate(problem, o);
  } catch (const std::exception& e) {
    run.status = Status::error;
    run.message = e.what();
  }
  d.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  d.status = run.status;
  d.message = run.message;
  d.stop_time = run.stop_time;
  d.cost = run.cost;
  const double e0 = problem.model().derived(problem.y0()).energy;
  for (std::size_t i = 0; i < run.output.t.size(); ++i) {
    const Derived x = problem.model().derived(run.output.y[i]);
    d.t.push_back(run.output.t[i]);
    d.energy_error.push_back(std::abs(x.energy - e0));
    d.rotation_defect.push_back(x.rotation_defect);
  }
  return d;
}

StableStepRecord stable_step_search(const SweepScene& s, const Integrator& m, const StabilitySpec& st) {
  StableStepRecord r;
  r.scene = s.scene.name;
  r.integrator = m.name();
  r.family = m.family();
  r.contact_threshold = st.contact_threshold;
  r.energy_threshold = st.energy_threshold;
  r.rotation_threshold = st.rotation_threshold;
  const BallParams& b = s.problem.model().params();
  const double energy_unit = b.mass * b.gravity * b.radius;
  const double e0 = s.problem.model().derived(s.problem.y0()).energy;
  for (double h = st.search_h_max; h >= st.search_h_min; h /= 2) {
    SweepTask task{0, 0, m.name(), h, kNaN};
    const RunRecord run = run_task(s, task, 5'000'000);
    StableStepTry t{h, run.status, run.error.contact, kNaN, run.rotation_drift};
    if (run.status == Status::ok) t.energy_error = std::max(run.energy_drift, std::abs(run.final_energy - e0)) / energy_unit;
    // an error below the reference's floor is as good as zero
    const double contact = std::isnan(run.error.contact) && run.status == Status::ok ? 0.0 : run.error.contact;
    r.tried.push_back(t);
    if (run.status == Status::ok && contact <= st.contact_threshold && t.energy_error <= st.energy_threshold &&
        t.rotation_defect <= st.rotation_threshold) {
      r.h = h;
      break;
    }
  }
  return r;
}

}  // namespace

StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress) {
  StabilityResults out;
  if (!spec.stability.enabled) return out;
  const StabilitySpec& st = spec.stability;

  // the scenes once at the search length, with their references
  SweepSpec search = spec;
  search.scenes = st.scenes;
  search.t_end = st.search_t_end;
  search.shard_count = 1;
  const std::vector<SweepScene> scenes = prepare_scenes(search);

  std::size_t index = 0;
  for (const SweepScene& s : scenes)
    for (const std::string& name : st.integrators) {
      if (mine(spec, index)) {
        // the run's own t_end overrides the shortened search length
        DriftRecord d = drift_run(s.problem, find_integrator(name), st);
        d.index = index;
        progress("stability: drift of " + name + " on " + s.scene.name + ": " + std::string(status_name(d.status)));
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
  for (const SweepScene& s : scenes)
    for (const std::string& name : fixed) {
      if (mine(spec, index)) {
        StableStepRecord r = stable_step_search(s, find_integrator(name), st);
        r.index = index;
        out.largest_stable_h.push_back(std::move(r));
      }
      ++index;
    }
  progress("stability: done");
  return out;
}

}  // namespace rb

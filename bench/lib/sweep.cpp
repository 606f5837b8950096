#include "bench/lib/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/so3.hpp"

namespace rb {

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

RunOptions options_of(const SweepScene& s, const SweepTask& task, long max_steps) {
  RunOptions o;
  o.t_end = s.problem.t_end();
  o.max_steps = max_steps;
  if (std::isnan(task.tol)) {
    o.h = task.h;
    // a fixed-step method lands on every output time, so outputs closer than
    // h would shorten its steps: keep the grid times that are multiples of h
    for (const double t : s.times) {
      const double k = std::round(t / task.h);
      if (std::abs(t - k * task.h) <= 1e-12 * t || t == s.times.back()) o.output_times.push_back(t);
    }
  } else {
    o.output_times = s.times;
    o.rtol = task.tol;
    o.atol = task.tol;
  }
  return o;
}

// Errors at t_end and the drift over the outputs.
void measure(const SweepScene& s, const RunResult& run, RunRecord& r) {
  const Problem& p = s.problem;
  const RollingBall& model = p.model();
  const double e0 = model.derived(p.y0()).energy;
  r.energy_drift = 0.0;
  r.rotation_drift = rotation_defect(rotation_of(p.y0()));
  for (const FlatState& y : run.output.y) {
    const Derived d = model.derived(y);
    r.energy_drift = std::max(r.energy_drift, std::abs(d.energy - e0));
    r.rotation_drift = std::max(r.rotation_drift, d.rotation_defect);
  }
  r.final_energy = model.derived(run.final_state).energy;
  r.error.floor = s.reference.error;
  if (run.status != Status::ok || s.reference.points.empty() || run.output.t.empty() ||
      run.output.t.back() != s.reference.t.back())
    return;

  const ReferencePoint& ref = s.reference.points.back();
  const ReferencePoint got = reference_point_of(p, run.output.y.back());
  const double values[4] = {(got.alpha - ref.alpha).norm(), (got.centre - ref.centre).norm(),
                            (got.omega - ref.omega).norm(), rotation_angle_between(ref.R, got.R)};
  // relative to the reference's size, with 1 as the scale floor (mixed
  // absolute-relative, as the IVP Test Set's scd)
  const double scales[4] = {std::max(1.0, ref.alpha.norm()), std::max(1.0, ref.centre.norm()),
                            std::max(1.0, ref.omega.norm()), 1.0};
  const char* names[4] = {"contact", "centre", "omega", "rotation"};
  double* slots[4] = {&r.error.contact, &r.error.centre, &r.error.omega, &r.error.rotation};
  double worst_relative = 0.0;
  for (int i = 0; i < 4; ++i) {
    worst_relative = std::max(worst_relative, values[i] / scales[i]);
    if (values[i] < r.error.floor) {
      r.error.below_floor.push_back(names[i]);
    } else {
      *slots[i] = values[i];
    }
  }
  // an error below the reference's floor counts as the floor: no more digits
  // can be claimed than the reference has
  if (std::isfinite(worst_relative)) r.error.scd = -std::log10(std::max({worst_relative, r.error.floor, 1e-16}));
}

}  // namespace

std::vector<SweepScene> prepare_scenes(const SweepSpec& spec) {
  std::vector<std::string> names = spec.scenes.empty() ? shipped_scene_names() : spec.scenes;
  std::vector<SweepScene> out;
  for (const std::string& name : names) {
    Scene scene = load_scene(name);
    if (spec.t_end > 0.0) scene.t_end = std::min(scene.t_end, spec.t_end);
    Problem problem = make_problem(scene);
    std::vector<double> times;
    for (int k = 1; k * spec.dt_out < scene.t_end - 1e-12; ++k) times.push_back(k * spec.dt_out);
    times.push_back(scene.t_end);
    std::ostringstream content;
    content.precision(17);
    content << read_file(scene.source) << "|t_end=" << scene.t_end;
    ReferenceSettings settings;
    settings.cache_dir = spec.cache_dir;
    Reference reference = make_reference(problem, content.str(), times, settings);
    out.push_back(SweepScene{std::move(scene), std::move(problem), content.str(), std::move(times), std::move(reference)});
  }
  return out;
}

std::vector<SweepTask> sweep_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes) {
  std::vector<std::string> methods = spec.integrators;
  if (methods.empty())
    for (const auto& m : registry()) methods.push_back(m->name());
  for (const std::string& m : methods) find_integrator(m);  // unknown names fail before any run
  std::vector<SweepTask> all;
  for (std::size_t s = 0; s < scenes.size(); ++s)
    for (const std::string& m : methods) {
      if (find_integrator(m).adaptive()) {
        for (double tol : spec.tols) all.push_back({all.size(), s, m, kNaN, tol});
      } else {
        for (double h : spec.hs) all.push_back({all.size(), s, m, h, kNaN});
      }
    }
  std::vector<SweepTask> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(spec.shard_count)) == spec.shard_index) mine.push_back(all[i]);
  return mine;
}

RunRecord run_task(const SweepScene& s, const SweepTask& task, long max_steps) {
  const Integrator& m = find_integrator(task.integrator);
  RunRecord r;
  r.index = task.index;
  r.scene = s.scene.name;
  r.integrator = m.name();
  r.family = m.family();
  r.declared_order = m.declared_order();
  r.rotation_order = m.rotation_order();
  r.adaptive = m.adaptive();
  r.needs_jacobian = m.needs_jacobian();
  r.h = task.h;
  r.rtol = r.atol = task.tol;
  RunResult run;
  try {
    run = m.integrate(s.problem, options_of(s, task, max_steps));
  } catch (const std::exception& e) {
    // an option the method cannot take is a failed run, not a failed sweep
    run.status = Status::error;
    run.message = e.what();
    run.final_state = s.problem.y0();
  }
  r.status = run.status;
  r.message = run.message;
  r.stop_time = run.stop_time;
  r.cost = run.cost;
  r.final_state = run.final_state;
  measure(s, run, r);
  return r;
}

std::vector<RunRecord> run_sweep(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                 const std::function<void(const std::string&)>& progress) {
  const std::vector<SweepTask> tasks = sweep_tasks(spec, scenes);
  std::vector<RunRecord> records(tasks.size());
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto report = [&](const char* phase, std::size_t done, std::size_t total, clock::time_point since,
                    const char* unit = "runs") {
    const double elapsed = std::chrono::duration<double>(clock::now() - since).count();
    const double eta = done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total - done) : 0.0;
    std::ostringstream s;
    s.precision(3);
    s << phase << ": " << done << "/" << total << " " << unit << ", " << elapsed << " s elapsed, about " << eta << " s left";
    progress(s.str());
  };

  // accuracy: parallel; a shared counter hands out tasks
  std::atomic<std::size_t> next{0}, done{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < tasks.size(); i = next++) {
      records[i] = run_task(scenes[tasks[i].scene], tasks[i], spec.max_steps);
      ++done;
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < std::max(1, spec.jobs); ++j) pool.emplace_back(worker);
  auto last_report = clock::now();
  while (done < tasks.size()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (clock::now() - last_report > std::chrono::seconds(2)) {
      report("accuracy", done, tasks.size(), start);
      last_report = clock::now();
    }
  }
  for (auto& t : pool) t.join();

  // timing: one run at a time on this thread, in rounds: round k times
  // repeat k of every run still within its budget, so that a slow spell of
  // this shared machine falls on every method alike and the median over
  // repeats leaves it out. Each timed call follows an untimed one of the
  // same run, so its code and data are as warm as in a repeat-by-repeat loop.
  const auto timing_start = clock::now();
  last_report = timing_start;
  std::vector<RunOptions> opts;
  std::vector<const Integrator*> methods;
  for (const SweepTask& task : tasks) {
    opts.push_back(options_of(scenes[task.scene], task, spec.max_steps));
    methods.push_back(&find_integrator(task.integrator));
  }
  std::vector<double> spent(tasks.size(), 0.0);
  const long total = static_cast<long>(tasks.size()) * spec.repeats;
  long timed = 0;
  for (int k = 0; k < spec.repeats; ++k) {
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      if (k > 0 && spent[i] >= spec.repeat_budget_s) continue;
      const Problem& problem = scenes[tasks[i].scene].problem;
      auto call = [&] {
        try {
          methods[i]->integrate(problem, opts[i]);
        } catch (const std::exception&) {
          // already recorded as a failed run
        }
      };
      call();
      const auto t0 = clock::now();
      call();
      const double dt = std::chrono::duration<double>(clock::now() - t0).count();
      records[i].wall_samples.push_back(dt);
      spent[i] += dt;
      ++timed;
      if (clock::now() - last_report > std::chrono::seconds(2)) {
        report("timing", static_cast<std::size_t>(timed), static_cast<std::size_t>(total), timing_start,
               "timed repeats (at most)");
        last_report = clock::now();
      }
    }
  }
  report("timing", static_cast<std::size_t>(timed), static_cast<std::size_t>(timed), timing_start, "timed repeats");
  return records;
}

}  // namespace rb

#include "bench/lib/sweep.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "bench/lib/drift.hpp"
#include "bench/lib/finer_steps.hpp"
#include "bench/lib/integrate_safely.hpp"
#include "bench/lib/regime_scenes.hpp"
#include "bench/lib/run_on_threads.hpp"
#include "bench/lib/trajectory_csv.hpp"
#include "integrators/driver.hpp"
#include "integrators/registry.hpp"
#include "integrators/step_size.hpp"
#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"
#include "problems/so3.hpp"
#include "problems/utf8.hpp"

namespace rb {

namespace {

// The options of a task recording the given outputs. A fixed-step method
// lands on every output time, so outputs closer than h would shorten its
// steps: of the outputs it keeps the multiples of h (and t_end).
RunOptions options_of(const SweepScene& s, const SweepTask& task, long max_steps, const std::vector<double>& outputs) {
  RunOptions o;
  o.t_end = s.problem.t_end();
  o.max_steps = max_steps;
  o.controller = task.controller;
  if (!task.tolerances.given()) {
    o.h = task.h;
    for (const double t : outputs) {
      const double k = std::round(t / task.h);
      if (std::abs(t - k * task.h) <= 1e-12 * t || t == outputs.back()) o.output_times.push_back(t);
    }
  } else {
    o.output_times = outputs;
    o.tolerances = task.tolerances;
  }
  return o;
}

// The errors of one state against one reference point: the components of
// kErrorComponents in their units, and worst, dimensionless.
struct PointErrors {
  std::array<double, kErrorComponentCount> values;
  double worst;
};

PointErrors point_errors(const SweepScene& s, const ReferencePoint& ref, const FlatState& y) {
  const ReferencePoint got = reference_point_of(s.problem, y);
  PointErrors e{component_distances(ref, got), 0.0};
  const double r = s.problem.model().params().radius;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i)
    e.worst = std::max(e.worst, e.values[i] / scale_value(kErrorComponents[i].scale, r, s.omega_scale));
  if (!std::isfinite(e.worst)) e.worst = kNaN;
  return e;
}

// Fills errors from the largest of each component over points (one point:
// the errors at t_end). A component below the reference's floor is NaN and
// listed; worst is NaN only when every component is.
void store(RunErrors& errors, const PointErrors& largest, double floor, int points) {
  errors.floor = floor;
  errors.points = points;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) {
    if (largest.values[i] < floor) {
      errors.below_floor.push_back(kErrorComponents[i].name);
    } else {
      errors.component(i) = largest.values[i];
    }
  }
  if (errors.below_floor.size() == kErrorComponentCount) {
    errors.below_floor.push_back("worst");
  } else {
    errors.worst = largest.worst;
  }
}

PointErrors largest_of(const PointErrors& a, const PointErrors& b) {
  PointErrors m = a;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i) m.values[i] = std::max(a.values[i], b.values[i]);
  m.worst = std::max(a.worst, b.worst);
  return m;
}

bool reached_end(const SweepScene& s, const RunResult& run) {
  return run.status == Status::ok && !s.reference.points.empty() && !run.output.t.empty() &&
         run.output.t.back() == s.reference.t.back();
}

}  // namespace

// Errors at t_end of the run that is timed.
void measure_end(const SweepScene& s, const RunResult& run, RunRecord& r) {
  r.error.floor = s.reference.error;
  if (!reached_end(s, run)) return;
  const ReferencePoint& ref = s.reference.points.back();
  const PointErrors e = point_errors(s, ref, run.output.y.back());
  store(r.error, e, s.reference.error, 1);
  // relative to the reference's size, with 1 as the scale floor (mixed
  // absolute-relative, as the IVP Test Set's scd), in the order of kErrorComponents
  const std::array<double, kErrorComponentCount> scales{
      std::max(1.0, ref.alpha.norm()), std::max(1.0, ref.centre.norm()), std::max(1.0, ref.omega.norm()), 1.0};
  double worst_relative = 0.0;
  for (std::size_t i = 0; i < kErrorComponentCount; ++i)
    worst_relative = std::max(worst_relative, e.values[i] / scales[i]);
  // an error below the reference's floor counts as the floor: no more digits
  // can be claimed than the reference has
  if (std::isfinite(worst_relative)) r.error.scd = -std::log10(std::max({worst_relative, r.error.floor, 1e-16}));
}

// The largest errors and the drift over the error grid, from a run that
// recorded it (every output time is one of the grid's, which the reference
// has). A run that stopped early keeps its drift, not its errors.
void measure_grid(const SweepScene& s, const RunResult& run, RunRecord& r) {
  const Drift drift = largest_drift(s.problem, run.output);
  r.energy_drift = drift.energy;
  r.energy_drift_on_group = drift.energy_on_group;
  r.rotation_drift = drift.rotation_defect;
  r.error_max.floor = s.reference.error;
  if (!reached_end(s, run)) return;
  PointErrors largest{};  // every component 0, worst 0
  std::size_t k = 0;      // both time lists increase: walk them together
  int points = 0;
  for (std::size_t i = 0; i < run.output.t.size(); ++i) {
    while (k < s.reference.t.size() && s.reference.t[k] < run.output.t[i]) ++k;
    if (k == s.reference.t.size() || s.reference.t[k] != run.output.t[i]) continue;
    largest = largest_of(largest, point_errors(s, s.reference.points[k], run.output.y[i]));
    ++points;
  }
  store(r.error_max, largest, s.reference.error, points);
}

namespace {

// A run whose process died or was killed (an isolated plug-in's): its
// state and cost are lost, and running it again would crash or hang again.
bool was_lost(Status status) { return status == Status::crashed || status == Status::timeout; }

double largest_omega(const Reference& reference) {
  double w = 0.0;
  for (const ReferencePoint& p : reference.points) w = std::max(w, p.omega.norm());
  return w > 0.0 ? w : 1.0;
}

// One name, one scene: the report keys references, runs and fits by the
// scene's name, so two scenes of one name (two files both "plane", a file
// named like a shipped scene) are refused, as is one scene given twice among
// the sweep's own (the first `own` of loaded; the studies' scenes after
// them may be the sweep's again).
void check_one_scene_per_name(const std::vector<std::string>& given, const std::vector<Scene>& loaded,
                              std::size_t own) {
  std::map<std::string, std::size_t> first;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    const auto [at, inserted] = first.try_emplace(loaded[i].name, i);
    if (inserted) continue;
    const std::string a = escaped_excerpt(given[at->second], 200), b = escaped_excerpt(given[i], 200);
    const std::string name = escaped_excerpt(loaded[i].name);
    if (loaded[at->second].text != loaded[i].text)
      throw InputError("'" + a + "' and '" + b + "' are two different scenes named '" + name + "'", "scenes");
    if (i < own) throw InputError("scene '" + name + "' is given twice ('" + a + "' and '" + b + "')", "scenes");
  }
}

}  // namespace

std::string progress_line(const std::string& phase, std::size_t done, std::size_t total, double elapsed_s,
                          const std::string& unit) {
  std::ostringstream s;
  s.precision(3);
  s << phase << ": " << done << "/" << total << " " << unit;
  if (done == 0) return s.str();  // nothing measured yet: an estimate of 0 s would say nothing
  const double eta = elapsed_s / static_cast<double>(done) * static_cast<double>(total - done);
  s << ", " << elapsed_s << " s elapsed, about " << eta << " s left";
  return s.str();
}

std::vector<SweepScene> prepare_scenes(const SweepSpec& spec, bool with_references,
                                       const std::function<void(const std::string&)>& progress) {
  // the regime study's scenes are generated from its grid, checked as files are
  const std::vector<Scene> generated = spec.regime ? regime_scenes(*spec.regime) : std::vector<Scene>{};
  std::vector<std::string> names = spec.scenes.empty() ? shipped_scene_names() : spec.scenes;
  if (spec.regime) {
    names.clear();
    for (const Scene& g : generated) names.push_back(g.name);
  }
  // every scene is read and checked before the first reference (minutes on
  // a long scene), its error naming the file
  std::vector<Scene> loaded = generated;
  if (!spec.regime)
    for (const std::string& name : names) {
      try {
        loaded.push_back(load_scene(name));
      } catch (const InputError& e) {
        throw InputError("in " + name + ": " + e.what(), "scenes");
      }
    }
  check_one_scene_per_name(names, loaded, loaded.size());
  if (with_references) {
    // the stability and horizon studies' scenes go into the same report, by
    // name: a file named like a shipped scene they run is refused too
    std::vector<std::string> given = names;
    std::vector<Scene> every = loaded;
    for (const auto& [enabled, list] : {std::pair{spec.stability.enabled, &spec.stability.scenes},
                                        std::pair{spec.horizon.enabled, &spec.horizon.scenes}})
      for (const std::string& name : enabled ? *list : std::vector<std::string>{})
        if (std::find(given.begin(), given.end(), name) == given.end()) {
          try {
            every.push_back(load_scene(name));
          } catch (const InputError& e) {
            throw InputError("in " + name + ": " + e.what(), "scenes");
          }
          given.push_back(name);
        }
    check_one_scene_per_name(given, every, loaded.size());
  }
  std::vector<SweepScene> out;
  const auto start = std::chrono::steady_clock::now();
  for (const std::string& name : names) {
    if (progress && with_references)
      progress(progress_line("references", out.size(), names.size(),
                             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                             "scenes") +
               " (next: " + name + ")");
    Scene scene = loaded[out.size()];
    if (spec.t_end > 0.0) scene.t_end = std::min(scene.t_end, spec.t_end);
    Problem problem = make_problem(scene);
    const double spacing = spec.dt_out > 0.0 ? spec.dt_out : spec.error_dt;
    std::vector<double> times = equally_spaced_outputs(spacing, scene.t_end);
    const std::vector<double> timed = spec.dt_out > 0.0 ? times : std::vector<double>{scene.t_end};
    std::ostringstream content;
    content.precision(17);
    content << scene.text << "|t_end=" << scene.t_end;
    ReferenceSettings settings;
    settings.cache_dir = spec.cache_dir;
    Reference reference;
    if (with_references) {
      reference = make_reference(problem, content.str(), times, settings);
    } else {
      reference.scene = scene.name;
      reference.kind = "none";
      reference.message = "not needed";
    }
    const double omega_scale = largest_omega(reference);
    out.push_back(SweepScene{std::move(scene), std::move(problem), content.str(), std::move(times), timed,
                             std::move(reference), omega_scale});
  }
  return out;
}

RunOptions timed_options(const SweepScene& s, const SweepTask& task, long max_steps) {
  return options_of(s, task, max_steps, s.timed_times);
}

std::size_t output_count(const Problem& problem, const RunOptions& options) {
  return output_times_of(problem, options).size();
}

double step_taken(double h, double t_end) {
  if (!(h > 0.0) || !(t_end > 0.0)) return h;  // refused by the method, as given
  // as drive_fixed_step divides an interval (the same slack)
  const double n = std::max(1.0, std::ceil(t_end / h - 1e-6));
  return t_end / n;
}

std::vector<SweepTask> sweep_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes) {
  std::vector<std::string> methods = spec.integrators;
  if (methods.empty())
    for (const auto& m : registry()) methods.push_back(m->name());
  for (const std::string& m : methods) find_integrator(m);  // unknown names fail before any run
  // each tolerance of the list checked once, as a run takes it
  std::vector<Tolerances> tolerances;
  for (const double tol : spec.tols) tolerances.emplace_back(tol, tol);
  // and each step (StepSize: finite, >= 0; 0 is a fixed-step method's refusal, a run's status)
  for (const double h : spec.hs) (void)StepSize(h);
  std::vector<SweepTask> all;
  for (std::size_t s = 0; s < scenes.size(); ++s)
    for (const std::string& m : methods) {
      if (find_integrator(m).adaptive()) {
        for (const Tolerances& tol : tolerances) all.push_back({all.size(), s, m, kNaN, tol, spec.controller});
      } else {
        // ladder values that give the same step on a short run are one run
        std::vector<double> taken;
        for (double h : spec.hs) {
          const double step = step_taken(h, scenes[s].problem.t_end());
          if (std::find(taken.begin(), taken.end(), step) != taken.end()) continue;
          taken.push_back(step);
          all.push_back({all.size(), s, m, step, {}, spec.controller});
        }
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
  r.method = m.info();
  r.h = task.h;
  if (task.tolerances.given()) {
    r.rtol = task.tolerances.rtol();
    r.atol = task.tolerances.atol();
  }
  const RunOptions timed = timed_options(s, task, max_steps);
  r.controller = controller_of(m.controller(), timed);
  const RunResult run = integrate_safely(m, s.problem, timed);
  r.status = run.status;
  r.message = valid_utf8(run.message);  // as every text the report takes from a method
  r.stop_time = run.stop_time;
  r.cost = run.cost;
  r.timed_outputs = output_count(s.problem, timed);
  r.final_state = run.final_state;
  r.final_point = reference_point_of(s.problem, run.final_state);
  r.final_energy = s.problem.model().derived(run.final_state).energy;
  measure_end(s, run, r);
  if (!m.adaptive() && run.status == Status::ok) r.reversibility = reversibility_after(m, s.problem, timed, run);
  const RunOptions grid = options_of(s, task, max_steps, s.times);
  if (was_lost(run.status)) return r;  // its state is lost: nothing to measure, and no second crash or wait
  if (grid.output_times == timed.output_times) {
    measure_grid(s, run, r);
    r.error_max_source = {true, run.cost.steps};
  } else {
    const RunResult on_grid = integrate_safely(m, s.problem, grid);
    measure_grid(s, on_grid, r);
    // the same steps end in the same state to the bit; equal counts alone
    // are not enough (GSL's implicit pairs land on outputs with as many steps)
    r.error_max_source = {on_grid.cost.steps == run.cost.steps && on_grid.cost.rejected == run.cost.rejected &&
                              on_grid.final_state == run.final_state,
                          on_grid.cost.steps};
    if (!r.error_max_source.same_steps) {
      // the grid run stepped differently (a method that lands on each
      // output): error_max stays the timed run's own, at the outputs it
      // recorded, and the grid run's is kept beside it
      r.error_grid = r.error_max;
      r.has_error_grid = true;
      const double energy = r.energy_drift, rotation = r.rotation_drift;  // the drift keeps the grid's points
      const double energy_on_group = r.energy_drift_on_group;
      r.error_max = RunErrors{};
      measure_grid(s, run, r);
      r.energy_drift = energy;
      r.rotation_drift = rotation;
      r.energy_drift_on_group = energy_on_group;
    }
    // the drivers check lift-off and curvature at outputs only: a failure
    // the grid run meets before the timed run's end or stop stands for the run
    if (on_grid.status != Status::ok && (run.status == Status::ok || on_grid.stop_time < run.stop_time)) {
      r.status = on_grid.status;
      r.message = on_grid.message + " (met by the untimed run on the error grid)";
      r.stop_time = on_grid.stop_time;
      r.final_state = on_grid.final_state;
      r.final_point = reference_point_of(s.problem, on_grid.final_state);
      r.final_energy = s.problem.model().derived(on_grid.final_state).energy;
      r.error = RunErrors{};
      r.error.floor = s.reference.error;
      r.reversibility.reset();
    }
  }
  return r;
}

namespace {

// The runs of tasks: accuracy in parallel, then the timed repeats.
std::vector<RunRecord> run_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                 const std::vector<SweepTask>& tasks,
                                 const std::function<void(const std::string&)>& progress) {
  std::vector<RunRecord> records(tasks.size());
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto report = [&](const char* phase, std::size_t done, std::size_t total, clock::time_point since,
                    const char* unit = "runs") {
    progress(progress_line(phase, done, total, std::chrono::duration<double>(clock::now() - since).count(), unit));
  };

  // accuracy: parallel (run_on_threads; isolated plug-ins alone afterwards)
  auto last_report = clock::now();
  run_on_threads(
      tasks.size(), spec.jobs, [&](std::size_t i) { return find_integrator(tasks[i].integrator).forks(); },
      [&](std::size_t i) { records[i] = run_task(scenes[tasks[i].scene], tasks[i], spec.max_steps); },
      [&](std::size_t done) {
        if (clock::now() - last_report > std::chrono::seconds(2)) {
          report("accuracy", done, tasks.size(), start);
          last_report = clock::now();
        }
      });

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
    opts.push_back(timed_options(scenes[task.scene], task, spec.max_steps));
    opts.back().warm_up = true;  // an isolated plug-in warms up in its own process
    methods.push_back(&find_integrator(task.integrator));
  }
  std::vector<double> spent(tasks.size(), 0.0);
  const long total = static_cast<long>(tasks.size()) * spec.repeats;
  long timed = 0;
  for (int k = 0; k < spec.repeats; ++k) {
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      if (k > 0 && spent[i] >= spec.repeat_budget_s) continue;
      if (was_lost(records[i].status)) continue;  // not timed: wall_s has no samples
      const Problem& problem = scenes[tasks[i].scene].problem;
      // the seconds an isolated run measured in its own process, else NaN
      auto call = [&] {
        try {
          return methods[i]->integrate(problem, opts[i]).solve_seconds;
        } catch (const std::exception&) {
          return kNaN;  // already recorded as a failed run
        }
      };
      call();
      const auto t0 = clock::now();
      const double solve_seconds = call();
      const double wall = std::chrono::duration<double>(clock::now() - t0).count();
      const double dt = std::isfinite(solve_seconds) ? solve_seconds : wall;
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

}  // namespace

std::vector<RunRecord> run_sweep(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                 const std::function<void(const std::string&)>& progress) {
  std::vector<RunRecord> records = run_tasks(spec, scenes, sweep_tasks(spec, scenes), progress);
  if (!spec.extend_ladders || spec.shard_count != 1) return records;
  for (int round = 0; round < kMaxLadderExtensions; ++round) {
    // unsharded: the indices so far are 0 .. size - 1
    const std::vector<SweepTask> finer = finer_step_tasks(spec, scenes, records, records.size());
    if (finer.empty()) break;
    progress(
        "orders: " + std::to_string(finer.size()) +
        " undecided fits (pre-asymptotic, straddling, too few points or failed runs) get a step half their smallest");
    std::vector<RunRecord> more = run_tasks(spec, scenes, finer, progress);
    records.insert(records.end(), more.begin(), more.end());
  }
  return records;
}

}  // namespace rb

#include "bench/lib/stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>
#include <utility>

#include "bench/lib/drift.hpp"
#include "bench/lib/integrate_safely.hpp"
#include "bench/lib/run_on_threads.hpp"
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
    d.energy_error_on_group.push_back(x.energy_on_group);
    d.rotation_defect.push_back(x.rotation_defect);
  }
  return d;
}

// The whole steps of size taken that reach T: T / taken where that is a
// whole number (to rounding), else the next one up.
long steps_to(double horizon, double taken) {
  const double n = horizon / taken;
  return std::abs(n - std::round(n)) <= 1e-9 * n ? std::lround(n) : static_cast<long>(std::ceil(n));
}

// The same problem starting at y (the next stretch of a rung's run).
Problem starting_at(const Problem& p, const FlatState& y) {
  return Problem(p.name(), p.model(), y, p.t_end(), p.domain(), nullptr, p.invariants());
}

// One rung: a fixed-step run at h to the last horizon, in stretches that
// end at the horizons (about search_outputs states recorded in each, at
// whole steps), judged at each horizon. It ends where the run stops, where
// it has blown up, and after the stretch in which it left a drift bound
// (no later failure is a blow-up: stability_verdict.hpp).
StableStepTry stable_step_try(const Problem& problem, const Integrator& m, double h, double energy_scale,
                              const StabilitySpec& st) {
  StableStepTry rung;
  rung.h = h;
  const std::vector<double>& horizons = st.horizons;
  const double taken = step_taken(h, horizons.back());
  const DriftMeter meter(problem);
  DriftSeries series;
  const auto record = [&](double at, const FlatState& y) {
    const Drift d = meter.at(y);
    series.t.push_back(at);
    series.energy.push_back(d.energy_on_group / energy_scale);
    series.energy_flat.push_back(d.energy / energy_scale);
    series.defect.push_back(d.rotation_defect);
  };
  FlatState y = problem.y0();
  long done = 0;  // whole steps so far
  for (std::size_t k = 0; k < horizons.size(); ++k) {
    const long end = std::max(done + 1, steps_to(horizons[k], taken));
    const long stretch = end - done;
    const double t0 = taken * static_cast<double>(done);
    RunOptions o;
    o.t_end = taken * static_cast<double>(stretch);
    o.h = taken;
    o.max_steps = stretch + 10;  // fixed steps: never the budget
    const long every = std::max(1L, stretch / std::max(1, st.search_outputs));
    for (long n = every; n < stretch; n += every) o.output_times.push_back(taken * static_cast<double>(n));
    const RunResult run = k == 0 ? integrate_safely(m, problem, o) : integrate_safely(m, starting_at(problem, y), o);
    rung.steps += run.cost.steps;
    for (std::size_t i = 0; i < run.output.t.size(); ++i)
      if (run.output.t[i] <= run.stop_time) record(t0 + run.output.t[i], run.output.y[i]);
    // the last state: the stretch's end, or the last valid state of a run that stopped
    if (series.t.empty() || t0 + run.stop_time > series.t.back()) record(t0 + run.stop_time, run.final_state);
    rung.stop_time = t0 + run.stop_time;
    rung.status = run.status;
    rung.message = valid_utf8(run.message);
    // a later stretch's run counts its times from the stretch's start
    if (k > 0 && !rung.message.empty()) {
      std::ostringstream where;
      where << "in the stretch from t = " << t0 << " s, whose times count from there: ";
      rung.message = where.str() + rung.message;
    }
    y = run.final_state;
    done = end;
    const bool stopped = run.status != Status::ok;
    // judged on the states up to the stretch's end (T itself where h divides it)
    rung.at.push_back(judge_horizon(stopped, series, taken * static_cast<double>(end), taken, st.bounds));
    rung.at.back().horizon = horizons[k];
    const HorizonVerdict& v = rung.at.back();
    if (stopped || v.blow_up != BlowUp::none) break;
    // out of its bounds with no blow-up in the steps after: decided at
    // every longer horizon (out of h*, not blown up), the run need not go on
    if (v.crossed_at + st.bounds.blow_up_steps * taken <= taken * static_cast<double>(end)) break;
  }
  rung.energy_crossed_at = first_past(series.t, series.energy, st.bounds.energy_fraction);
  rung.defect_crossed_at = first_past(series.t, series.defect, st.bounds.rotation_defect);
  rung.energy_blown_at = first_past(series.t, series.energy, st.bounds.blow_up_energy);
  rung.defect_blown_at = first_past(series.t, series.defect, st.bounds.blow_up_defect);
  rung.cut_short = rung.status == Status::ok && rung.at.size() < horizons.size();
  rung.stable = rung.at.size() == horizons.size() && rung.at.back().within();
  return rung;
}

StableStepRecord stable_step_search(const SweepScene& s, const Integrator& m, const StabilitySpec& st) {
  StableStepRecord r;
  r.scene = s.scene.name;
  r.method = m.info();
  r.horizons = st.horizons;
  r.energy_scale = energy_scale(s.problem);
  r.bounds = st.bounds;
  if (st.horizons.empty()) return r;  // nothing to read (the option refuses an empty list)
  // downward from the largest step, which fails within a few steps where it
  // fails, to the first rung that keeps every bound to the last horizon
  std::vector<double> ladder;
  for (double h = st.search_h_min; h <= st.search_h_max * (1 + 1e-12); h *= 2) ladder.push_back(h);
  for (auto h = ladder.rbegin(); h != ladder.rend(); ++h) {
    r.tried.push_back(stable_step_try(s.problem, m, *h, r.energy_scale, st));
    if (r.tried.back().stable) break;
  }
  std::reverse(r.tried.begin(), r.tried.end());
  read_limits(r, st.search_h_max);
  return r;
}

}  // namespace

RungAt rung_at(const StableStepTry& rung, std::size_t horizon) {
  RungAt a;
  if (rung.at.empty()) return a;
  const std::size_t k = std::min(horizon, rung.at.size() - 1);
  a.verdict = &rung.at[k];
  a.blow_up = a.verdict->blow_up;
  a.blown_up = a.blow_up != BlowUp::none;
  // a rung cut short before T keeps its blow-up and its crossed bounds
  a.within = horizon < rung.at.size() && a.verdict->within();
  return a;
}

void read_limits(StableStepRecord& r, double h_max) {
  const std::size_t n = r.horizons.size();
  r.blow_up.assign(n, BlowUpStep{});
  r.drift_limited.assign(n, DriftLimit{});
  for (std::size_t k = 0; k < n; ++k) {
    BlowUpStep& b = r.blow_up[k];
    DriftLimit& d = r.drift_limited[k];
    b.horizon = d.horizon = r.horizons[k];
    for (std::size_t i = 0; i < r.tried.size(); ++i) {
      const RungAt a = rung_at(r.tried[i], k);
      if (a.blown_up && std::isnan(b.h)) {
        b.h = r.tried[i].h;
        b.cause = a.blow_up;
        b.status = r.tried[i].status;
        b.smallest_tried = i == 0;
      }
      if (!std::isnan(d.next_h)) continue;
      if (a.within) {
        d.h = r.tried[i].h;
        continue;
      }
      // the first rung from below that failed at T: what ended it
      const StableStepTry& t = r.tried[i];
      d.next_h = t.h;
      d.blow_up = a.blow_up;
      d.next_status = t.status;
      const double horizon = r.horizons[k];
      const double e = t.energy_crossed_at, q = t.defect_crossed_at;
      const bool energy = e <= horizon * (1 + 1e-12), defect = q <= horizon * (1 + 1e-12);
      if (a.blown_up) {
        d.limited_by = "blow-up";
      } else if (energy && (!defect || e <= q)) {
        d.limited_by = kEnergyQuantity;
        d.value = a.verdict ? a.verdict->energy_error : kNaN;
        d.bound = r.bounds.energy_fraction;
      } else if (defect) {
        d.limited_by = kDefectQuantity;
        d.value = a.verdict ? a.verdict->rotation_defect : kNaN;
        d.bound = r.bounds.rotation_defect;
      }
    }
    d.at_limit = std::isnan(d.next_h) && !std::isnan(d.h) && d.h >= h_max * (1 - 1e-12);
  }
  for (std::size_t k = 1; k < n; ++k) {
    const double a = r.blow_up[k].h, b = r.blow_up[0].h;
    if (!(a == b || (std::isnan(a) && std::isnan(b)))) r.blow_up_moves = true;
  }
  // the records of before: the drift-limited step at the last horizon and its accuracy
  if (n > 0) {
    const DriftLimit& last = r.drift_limited.back();
    r.h = last.h;
    r.horizon = r.horizons.back();
    r.at_limit = last.at_limit;
    for (const StableStepTry& t : r.tried)
      if (t.h == last.h && !t.at.empty()) {
        r.energy_error = t.last().energy_error_flat;
        r.energy_error_on_group = t.last().energy_error;
        r.rotation_defect = t.last().rotation_defect;
      }
  }
}

StabilityResults run_stability(const SweepSpec& spec, const std::function<void(const std::string&)>& progress) {
  StabilityResults out;
  if (!spec.stability.enabled) return out;
  const StabilitySpec& st = spec.stability;

  // the scenes once at the search length; stability needs no reference
  SweepSpec search = spec;
  search.scenes = st.scenes;
  search.t_end = st.horizons.empty() ? 0.0 : st.horizons.back();
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
  // the searches are independent: they share --jobs threads (run_on_threads)
  std::vector<std::pair<std::size_t, std::size_t>> searches;  // (scene, method) of this shard's
  std::vector<std::size_t> indices;
  for (std::size_t si = 0; si < scenes.size(); ++si)
    for (std::size_t mi = 0; mi < fixed.size(); ++mi, ++index)
      if (mine(spec, index)) {
        searches.emplace_back(si, mi);
        indices.push_back(index);
      }
  std::vector<StableStepRecord> records(searches.size());
  const auto search_start = elapsed();
  std::mutex report_lock;
  std::size_t searched = 0;
  run_on_threads(
      searches.size(), spec.jobs, [&](std::size_t k) { return find_integrator(fixed[searches[k].second]).forks(); },
      [&](std::size_t k) {
        StableStepRecord r =
            stable_step_search(scenes[searches[k].first], find_integrator(fixed[searches[k].second]), st);
        r.index = indices[k];
        const std::lock_guard<std::mutex> hold(report_lock);
        if (++searched % 8 == 0)
          progress(progress_line("stability: blow-up and drift-limited steps", searched, searches.size(),
                                 elapsed() - search_start, "methods x scenes"));
        records[k] = std::move(r);
      },
      [](std::size_t) {});
  out.largest_stable_h = std::move(records);
  progress("stability: done");
  return out;
}

}  // namespace rb

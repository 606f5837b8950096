#include "bench/lib/horizon.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <mutex>

#include "bench/lib/drift.hpp"
#include "bench/lib/integrate_safely.hpp"
#include "bench/lib/order_fit.hpp"
#include "bench/lib/run_on_threads.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "problems/utf8.hpp"

namespace rb {

using json = nlohmann::json;

namespace {

// This thread's CPU time: a run's price that other threads and programs on
// the machine do not inflate as they do its wall time.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The output step counts: the samples and every `every` steps, merged.
std::vector<long> output_steps(const std::vector<long>& samples, long steps, long every) {
  std::vector<long> at = samples;
  for (long n = every; n <= steps; n += every) at.push_back(n);
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  return at;
}

std::string fixed(double v, const char* format) {
  if (!std::isfinite(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

json fit_json(const GrowthFit& f) {
  return {{"p", number(f.p)},
          {"ci95", number(f.ci95)},
          {"p_early", number(f.p_early)},
          {"p_late", number(f.p_late)},
          {"log10_c", number(f.log10_c)},
          {"t_from", f.t_from},
          {"t_to", f.t_to},
          {"points", f.points},
          {"largest", number(f.largest)},
          {"rounding_level", f.rounding_level},
          {"at_rounding", f.at_rounding},
          {"asymptotic", f.asymptotic},
          {"why_none", f.why_none.empty() ? json(nullptr) : json(f.why_none)}};
}

}  // namespace

GrowthFit fit_growth(const std::vector<double>& t, const std::vector<double>& err, double t_from, double t_to,
                     double rounding) {
  GrowthFit f;
  f.t_from = t_from;
  f.t_to = t_to;
  f.rounding_level = rounding;
  std::vector<double> x, y;
  for (std::size_t i = 0; i < t.size() && i < err.size(); ++i) {
    // the slack keeps a window edge that is a sample time itself in it
    if (!(t[i] >= t_from * (1 - 1e-12) && t[i] <= t_to * (1 + 1e-12)) || !std::isfinite(err[i])) continue;
    if (!(f.largest >= err[i])) f.largest = err[i];
    if (err[i] > 0.0) x.push_back(std::log10(t[i])), y.push_back(std::log10(err[i]));
  }
  f.points = static_cast<int>(x.size());
  f.at_rounding = std::isfinite(f.largest) && f.largest <= rounding;
  if (f.points < kMinGrowthPoints) {
    f.why_none = "only " + std::to_string(f.points) + " samples with a value > 0 in the window (at least " +
                 std::to_string(kMinGrowthPoints) + ")";
    return f;
  }
  const LineFit line = fit_line(x, y);
  f.p = line.slope;
  f.ci95 = line.slope_ci95;
  f.log10_c = line.intercept;
  // the halves of the window in log t, each with the middle sample
  const double middle = 0.5 * (std::log10(t_from) + std::log10(t_to));
  std::vector<double> xe, ye, xl, yl;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] <= middle + 1e-12) xe.push_back(x[i]), ye.push_back(y[i]);
    if (x[i] >= middle - 1e-12) xl.push_back(x[i]), yl.push_back(y[i]);
  }
  f.p_early = fit_line(xe, ye).slope;
  f.p_late = fit_line(xl, yl).slope;
  if (!std::isfinite(f.p)) f.why_none = "every sample in the window is at one time";
  return f;
}

std::vector<long> horizon_sample_steps(long steps, int per_decade) {
  std::vector<long> n;
  for (int k = 0;; ++k) {
    const long v = std::lround(std::pow(10.0, static_cast<double>(k) / per_decade));
    if (v >= steps) break;
    if (n.empty() || v > n.back()) n.push_back(v);
  }
  n.push_back(steps);
  return n;
}

double rounding_level(long steps, double scale) {
  return 100.0 * std::numeric_limits<double>::epsilon() * std::sqrt(static_cast<double>(steps)) * scale;
}

HorizonRecord horizon_run(const Problem& problem, const Integrator& m, const HorizonSpec& spec) {
  HorizonRecord r;
  r.scene = problem.name();
  r.r_feeds_back = problem.model().anisotropic();
  r.method = m.info();
  r.h = spec.h;
  r.steps = spec.steps;
  r.t_end = spec.h * static_cast<double>(spec.steps);
  r.energy_scale = energy_scale(problem);
  const std::vector<long> samples = horizon_sample_steps(spec.steps, spec.samples_per_decade);
  const long every = std::max(1L, spec.steps / std::max(1L, spec.dense_outputs));
  RunOptions o;
  o.t_end = r.t_end;
  o.h = spec.h;
  o.max_steps = 2 * spec.steps + 10;
  // every output a whole number of steps, so that no step is shortened to land
  for (const long n : output_steps(samples, spec.steps, every)) o.output_times.push_back(spec.h * n);
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  const RunResult run = integrate_safely(m, problem, o);
  r.status = run.status;
  r.message = run.message;
  r.stop_time = run.stop_time;
  r.cost = run.cost;
  const DriftMeter meter(problem);
  const InvariantMeter invariants(problem);
  for (const std::string& name : invariants.names()) r.invariants.push_back({name, {}, {}});
  // the envelope: the largest of each over the states measured in the
  // sample's window (the previous sample's step, its own step], so that a
  // late window does not carry an early peak as a running maximum would
  double energy = kNaN, defect = kNaN;
  std::vector<double> invariant(r.invariants.size(), kNaN);
  // a non-finite value does not raise the largest (NaN fails >=)
  const auto raise = [](double& largest, double value) {
    if (!(largest >= value) && std::isfinite(value)) largest = value;
  };
  std::size_t next = 0;
  for (std::size_t i = 0; i < run.output.t.size(); ++i) {
    const Drift d = meter.at(run.output.y[i]);
    raise(energy, d.energy);
    raise(defect, d.rotation_defect);
    if (!invariant.empty()) {
      const std::vector<double> e = invariants.errors(run.output.y[i]);
      for (std::size_t k = 0; k < e.size(); ++k) raise(invariant[k], e[k]);
    }
    const long n = std::lround(run.output.t[i] / spec.h);
    while (next < samples.size() && samples[next] < n) ++next;
    if (next < samples.size() && samples[next] == n) {
      r.t.push_back(run.output.t[i]);
      r.energy_error.push_back(energy);
      r.rotation_defect.push_back(defect);
      energy = defect = kNaN;
      for (std::size_t k = 0; k < invariant.size(); ++k) {
        r.invariants[k].error.push_back(invariant[k]);
        invariant[k] = kNaN;
      }
    }
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpu_s = thread_cpu_seconds() - cpu_start;
  const double t_from = r.t_end * std::pow(10.0, -spec.fit_decades);
  r.energy_fit = fit_growth(r.t, r.energy_error, t_from, r.t_end, rounding_level(spec.steps, r.energy_scale));
  r.defect_fit = fit_growth(r.t, r.rotation_defect, t_from, r.t_end, rounding_level(spec.steps, 1.0));
  // the invariants' errors are relative: their rounding level is the defect's
  for (InvariantSeries& s : r.invariants)
    s.fit = fit_growth(r.t, s.error, t_from, r.t_end, rounding_level(spec.steps, 1.0));
  std::vector<GrowthFit*> fits = {&r.energy_fit, &r.defect_fit};
  for (InvariantSeries& s : r.invariants) fits.push_back(&s.fit);
  for (GrowthFit* f : fits) f->asymptotic = std::abs(f->p_late - f->p_early) <= spec.asymptotic_spread;
  if (r.status != Status::ok) {
    // a run that stopped has no growth law to its end: its samples stay, no fit
    for (GrowthFit* f : fits) {
      const double rounding = f->rounding_level;
      *f = GrowthFit{};
      f->t_from = t_from;
      f->t_to = r.t_end;
      f->rounding_level = rounding;
      f->why_none =
          "the run stopped at t = " + fixed(r.stop_time, "%.6g") + " (" + std::string(status_name(r.status)) + ")";
    }
  }
  return r;
}

void check_horizon(const HorizonSpec& spec) {
  if (!spec.enabled) return;
  if (!(spec.steps >= 1000 && spec.steps <= 100'000'000))
    throw InputError("expected a whole number of steps from 1000 to 100000000, got " + std::to_string(spec.steps),
                     "horizon-steps");
  if (!(spec.h > 0.0 && std::isfinite(spec.h))) throw InputError("the step must be a finite number > 0", "horizon-h");
  if (spec.samples_per_decade < 1 || !(spec.fit_decades > 0.0) || spec.dense_outputs < 1)
    throw InputError("samples per decade, fit decades and dense outputs must be > 0", "horizon");
  if (spec.scenes.empty()) throw InputError("the horizon study needs at least one scene", "horizon-scenes");
  if (spec.integrators.empty())
    throw InputError("the horizon study needs at least one integrator", "horizon-integrators");
  for (const std::string& name : spec.integrators)
    if (find_integrator(name).adaptive())
      throw InputError("'" + name + "' is adaptive: the horizon study takes fixed steps", "horizon-integrators");
  for (const std::string& scene : spec.scenes) (void)load_scene(scene);
}

long parse_horizon_steps(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !(v >= 1000.0 && v <= 1e8) || v != std::floor(v))
    throw InputError(
        "expected a whole number of steps from 1000 to 1e8 (e.g. 100000 or 1e6), got '" + valid_utf8(text) + "'",
        "horizon-steps");
  return static_cast<long>(v);
}

std::vector<long> price_coarsenings(const HorizonSpec& spec) {
  std::vector<long> ks;
  for (const long k : spec.coarsenings)
    if (k > 1 && spec.steps % k == 0 && std::find(ks.begin(), ks.end(), k) == ks.end()) ks.push_back(k);
  return ks;
}

HorizonResults run_horizon(const SweepSpec& spec, const std::function<void(const std::string&)>& progress) {
  HorizonResults out;
  const HorizonSpec& hs = spec.horizon;
  if (!hs.enabled) return out;
  const auto start = std::chrono::steady_clock::now();
  // one block of scenes x methods per step: the study's h, then each price run's k h
  std::vector<long> coarsenings = {1};
  for (const long k : price_coarsenings(hs)) coarsenings.push_back(k);
  const std::size_t block = hs.scenes.size() * hs.integrators.size();
  const std::size_t total = block * coarsenings.size();
  std::vector<Problem> problems;
  for (const std::string& scene : hs.scenes) problems.push_back(make_problem(load_scene(scene)));
  // this shard's runs by their index in the full study, scenes outer
  std::vector<std::size_t> mine;
  for (std::size_t index = 0; index < total; ++index)
    if (static_cast<int>(index % static_cast<std::size_t>(spec.shard_count)) == spec.shard_index) mine.push_back(index);
  std::vector<HorizonRecord> records(mine.size());
  std::mutex report_lock;
  std::size_t done = 0;
  const auto run_one = [&](std::size_t k) {
    const std::size_t index = mine[k], in_block = index % block;
    const long coarsening = coarsenings[index / block];
    HorizonSpec run_spec = hs;
    run_spec.h = hs.h * static_cast<double>(coarsening);
    run_spec.steps = hs.steps / coarsening;
    const std::string& name = hs.integrators[in_block % hs.integrators.size()];
    HorizonRecord r = horizon_run(problems[in_block / hs.integrators.size()], find_integrator(name), run_spec);
    r.index = index;
    r.coarsening = coarsening;
    std::string invariants;
    for (const InvariantSeries& s : r.invariants)
      invariants += ", " + s.name + " p = " + fixed(s.fit.p, "%.2f") + (s.fit.at_rounding ? " (rounding)" : "");
    const std::lock_guard<std::mutex> hold(report_lock);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string at = coarsening == 1 ? "" : " at " + std::to_string(coarsening) + " h";
    progress("horizon: " + name + " on " + r.scene + at + ": " + std::string(status_name(r.status)) + ", energy p = " +
             fixed(r.energy_fit.p, "%.2f") + ", rotation defect p = " + fixed(r.defect_fit.p, "%.2f") +
             (r.defect_fit.at_rounding ? " (rounding)" : "") + invariants + ", " + fixed(r.cpu_s, "%.2f") + " s CPU (" +
             progress_line("horizon", ++done, mine.size(), elapsed) + ")");
    records[k] = std::move(r);
  };
  // the runs are independent and each is timed by its own thread's CPU
  // clock, so they share --jobs threads (run_on_threads)
  run_on_threads(
      mine.size(), spec.jobs,
      [&](std::size_t k) { return find_integrator(hs.integrators[mine[k] % hs.integrators.size()]).forks(); }, run_one,
      [](std::size_t) {});
  out.runs = std::move(records);
  return out;
}

namespace {

// The rounding level a run's fit recorded for a series; NaN without one.
double rounding_of(const json& run, const char* key) {
  const json* f = run.contains("fit") && run["fit"].contains(key) ? &run["fit"][key] : nullptr;
  return f && f->contains("rounding_level") && (*f)["rounding_level"].is_number() ? (*f)["rounding_level"].get<double>()
                                                                                  : kNaN;
}

// Both arrays of one length, null at the same samples, rising above
// kSameSeriesRise times the rounding level and nowhere further apart than it.
bool same_series(const json& a, const json& b, double rounding) {
  if (!a.is_array() || !b.is_array() || a.size() != b.size() || a.empty() || !(rounding > 0.0)) return false;
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].is_number() != b[i].is_number()) return false;
    if (!a[i].is_number()) continue;
    const double x = a[i].get<double>(), y = b[i].get<double>();
    if (!(std::abs(x - y) <= rounding)) return false;
    largest = std::max({largest, std::abs(x), std::abs(y)});
  }
  return largest >= kSameSeriesRise * rounding;
}

}  // namespace

namespace {

// A first integral's error series and its fit's rounding level in a run, by name (null, NaN when absent).
json invariant_error(const json& run, const std::string& name, double* rounding) {
  *rounding = kNaN;
  if (!run.contains("invariants") || !run["invariants"].is_array()) return json();
  for (const json& i : run["invariants"])
    if (i.value("name", "") == name) {
      if (i.contains("fit") && i["fit"].contains("rounding_level") && i["fit"]["rounding_level"].is_number())
        *rounding = i["fit"]["rounding_level"].get<double>();
      return i.value("error", json());
    }
  return json();
}

}  // namespace

void mark_same_series(json& runs) {
  const auto index = [&](std::size_t i) { return runs[i].value("index", i); };
  // the earliest earlier run of run i's scene with the same times and a series that series(run) equals
  const auto first_twin = [&](std::size_t i, const auto& series) {
    double ri = kNaN;
    const json a = series(runs[i], &ri);
    std::size_t first = runs.size();
    for (std::size_t j = 0; j < runs.size(); ++j) {
      if (!(index(j) < index(i) && (first == runs.size() || index(j) < index(first)) &&
            runs[j].value("scene", "") == runs[i].value("scene", "") &&
            runs[j].value("t", json()) == runs[i].value("t", json())))
        continue;
      double rj = kNaN;
      const json b = series(runs[j], &rj);
      if (same_series(b, a, std::max(ri, rj))) first = j;
    }
    return first < runs.size() ? json(runs[first].value("integrator", "")) : json();
  };
  for (std::size_t i = 0; i < runs.size(); ++i) {
    json same = {{"energy_error", nullptr}, {"rotation_defect", nullptr}};
    for (const char* key : {"energy_error", "rotation_defect"})
      same[key] = first_twin(i, [&](const json& run, double* rounding) {
        *rounding = rounding_of(run, key);
        return run.value(key, json());
      });
    // each first integral's error, by name
    json invariants = json::object();
    if (runs[i].contains("invariants") && runs[i]["invariants"].is_array())
      for (const json& inv : runs[i]["invariants"]) {
        const std::string name = inv.value("name", "");
        invariants[name] =
            first_twin(i, [&](const json& run, double* rounding) { return invariant_error(run, name, rounding); });
      }
    same["invariants"] = invariants;
    runs[i]["same_as"] = same;
  }
}

json horizon_json(const HorizonResults& results) {
  json runs = json::array();
  for (const HorizonRecord& r : results.runs) {
    json invariants = json::array();
    for (const InvariantSeries& s : r.invariants) {
      json error = json::array();
      for (const double e : s.error) error.push_back(number(e));
      invariants.push_back({{"name", s.name}, {"error", error}, {"fit", fit_json(s.fit)}});
    }
    runs.push_back({{"index", r.index},
                    {"scene", r.scene},
                    {"r_feeds_back", r.r_feeds_back},
                    {"integrator", r.method.name},
                    {"family", r.method.family},
                    {"declared_order", r.method.declared_order},
                    {"on_group", r.method.on_group},
                    {"coarsening", r.coarsening},
                    {"h", r.h},
                    {"steps_planned", r.steps},
                    {"t_end", r.t_end},
                    {"status", std::string(status_name(r.status))},
                    {"message", r.message},
                    {"stop_time", r.stop_time},
                    {"steps", r.cost.steps},
                    {"rhs_evals", r.cost.rhs_evals},
                    {"exp_evals", r.cost.exp_evals},
                    {"jacobian_evals", r.cost.jacobian_evals},
                    {"newton_iterations", r.cost.newton_iterations},
                    {"newton_failures", r.cost.newton_failures},
                    {"wall_s", r.wall_s},
                    {"cpu_s", r.cpu_s},
                    {"energy_scale", r.energy_scale},
                    {"t", r.t},
                    {"energy_error", r.energy_error},
                    {"rotation_defect", r.rotation_defect},
                    {"fit", {{"energy_error", fit_json(r.energy_fit)}, {"rotation_defect", fit_json(r.defect_fit)}}},
                    {"invariants", invariants}});
  }
  mark_same_series(runs);
  return {{"runs", runs}};
}

json horizon_options_json(const HorizonSpec& s) {
  std::vector<std::string> scenes;
  for (const std::string& scene : s.scenes) scenes.push_back(valid_utf8(scene));
  return {{"enabled", s.enabled},
          {"scenes", scenes},
          {"integrators", s.integrators},
          {"h", s.h},
          {"steps", s.steps},
          {"samples_per_decade", s.samples_per_decade},
          {"fit_decades", s.fit_decades},
          {"dense_outputs", s.dense_outputs},
          {"asymptotic_spread", s.asymptotic_spread},
          {"coarsenings", price_coarsenings(s)},
          {"same_series_rise", kSameSeriesRise}};
}

}  // namespace rb

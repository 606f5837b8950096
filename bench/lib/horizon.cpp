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

// The output step counts: the samples, every `every` steps, and in each
// window (previous sample, sample] per_window steps evenly spaced (all of
// a shorter window's), merged: an early window, a few hundred steps long,
// gets as many states as a late one, so its largest is not a few states'
std::vector<long> output_steps(const std::vector<long>& samples, long steps, long every, long per_window) {
  std::vector<long> at = samples;
  for (long n = every; n <= steps; n += every) at.push_back(n);
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const long from = samples[k - 1], length = samples[k] - from, count = std::min(length, per_window);
    for (long j = 1; j < count; ++j) at.push_back(from + (j * length) / count);
  }
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

json class_json(GrowthClass c) { return c == GrowthClass::none ? json(nullptr) : json(growth_class_name(c)); }

json fit_json(const GrowthFit& f) {
  json decades = json::array();
  for (const DecadeSlope& d : f.decades)
    decades.push_back(
        {{"t_from", d.t_from}, {"t_to", d.t_to}, {"p", number(d.p)}, {"ci95", number(d.ci95)}, {"points", d.points}});
  return {{"class", class_json(f.growth_class)},
          {"reason", f.reason},
          {"p", number(f.p)},
          {"ci95", number(f.ci95)},
          {"log10_c", number(f.log10_c)},
          {"t_from", f.t_from},
          {"t_to", f.t_to},
          {"points", f.points},
          {"largest", number(f.largest)},
          {"rounding_level", f.rounding_level},
          {"at_rounding", f.at_rounding},
          {"decades", decades},
          {"p_earlier", number(f.p_earlier)},
          {"ci95_earlier", number(f.ci95_earlier)},
          {"p_last", number(f.p_last)},
          {"ci95_last", number(f.ci95_last)}};
}

// "linear p = 1.01", "undecided", "rounding", "-" (no fit): for the progress line
std::string class_text(const GrowthFit& f) {
  if (f.growth_class == GrowthClass::none) return "-";
  const std::string name = growth_class_name(f.growth_class);
  return decided(f.growth_class) && f.growth_class != GrowthClass::rounding ? name + " p = " + fixed(f.p, "%.2f")
                                                                            : name;
}

GrowthRules rules_of(const HorizonSpec& spec) {
  GrowthRules rules;
  rules.decades = spec.fit_decades;
  rules.spread = spec.asymptotic_spread;
  return rules;
}

// the largest finite value of a series; NaN without one
double largest_of(const std::vector<double>& v) {
  double largest = kNaN;
  for (const double x : v)
    if (std::isfinite(x) && !(largest >= x)) largest = x;
  return largest;
}

}  // namespace

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
  r.study_steps = spec.steps;
  r.t_end = spec.h * static_cast<double>(spec.steps);
  r.energy_scale = energy_scale(problem);
  const std::vector<long> samples = horizon_sample_steps(spec.steps, spec.samples_per_decade);
  const long every = std::max(1L, spec.steps / std::max(1L, spec.dense_outputs));
  RunOptions o;
  o.t_end = r.t_end;
  o.h = spec.h;
  o.max_steps = 2 * spec.steps + 10;
  // every output a whole number of steps, so that no step is shortened to land
  for (const long n : output_steps(samples, spec.steps, every, spec.window_outputs))
    o.output_times.push_back(spec.h * n);
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  const RunResult run = integrate_safely(m, problem, o);
  r.status = run.status;
  r.message = run.message;
  r.stop_time = run.stop_time;
  r.cost = run.cost;
  const DriftMeter meter(problem);
  const InvariantMeter invariants(problem);
  for (std::size_t k = 0; k < invariants.names().size(); ++k)
    r.invariants.push_back({invariants.names()[k], invariants.kinds()[k], {}, {}});
  // the envelope: the largest of each over the states measured in the
  // sample's window (the previous sample's step, its own step], so that a
  // late window does not carry an early peak as a running maximum would
  double energy = kNaN, defect = kNaN, energy_on_group = kNaN;
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
    raise(energy_on_group, d.energy_on_group);
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
      r.energy_error_on_group.push_back(energy_on_group);
      energy = defect = energy_on_group = kNaN;
      for (std::size_t k = 0; k < invariant.size(); ++k) {
        r.invariants[k].error.push_back(invariant[k]);
        invariant[k] = kNaN;
      }
    }
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpu_s = thread_cpu_seconds() - cpu_start;
  const GrowthRules rules = rules_of(spec);
  r.energy_fit = classify_growth(r.t, r.energy_error, rounding_level(spec.steps, r.energy_scale), rules);
  r.defect_fit = classify_growth(r.t, r.rotation_defect, rounding_level(spec.steps, 1.0), rules);
  r.energy_on_group_fit =
      classify_growth(r.t, r.energy_error_on_group, rounding_level(spec.steps, r.energy_scale), rules);
  // the invariants' errors are relative: their rounding level is the defect's
  for (InvariantSeries& s : r.invariants) s.fit = classify_growth(r.t, s.error, rounding_level(spec.steps, 1.0), rules);
  if (r.status != Status::ok) {
    // a run that stopped has no growth law to its end: its samples stay, no fit
    std::vector<GrowthFit*> fits = {&r.energy_fit, &r.defect_fit, &r.energy_on_group_fit};
    for (InvariantSeries& s : r.invariants) fits.push_back(&s.fit);
    for (GrowthFit* f : fits) {
      const double rounding = f->rounding_level;
      *f = GrowthFit{};
      f->t_from = r.t_end * std::pow(10.0, -spec.fit_decades);
      f->t_to = r.t_end;
      f->rounding_level = rounding;
      f->reason =
          "the run stopped at t = " + fixed(r.stop_time, "%.6g") + " (" + std::string(status_name(r.status)) + ")";
    }
  }
  return r;
}

bool any_undecided(const HorizonRecord& r) {
  for (const GrowthFit* f : {&r.energy_fit, &r.energy_on_group_fit, &r.defect_fit})
    if (f->growth_class == GrowthClass::undecided) return true;
  return false;
}

HorizonRecord horizon_decades(const Problem& problem, const Integrator& m, const HorizonSpec& spec) {
  HorizonSpec decade = spec;
  HorizonRecord r = horizon_run(problem, m, decade);
  std::vector<EarlierRun> earlier;
  const long most = std::max(spec.steps, spec.steps_max);
  while (r.status == Status::ok && any_undecided(r)) {
    const long next = 10 * decade.steps;
    const double predicted = 10.0 * r.cpu_s;
    if (next > most) {
      r.budget_reason = "the next decade, " + std::to_string(next) + " steps, is past the study's most, " +
                        std::to_string(most) + " (--horizon-steps-max)";
      break;
    }
    if (!(predicted <= spec.cpu_max_s)) {
      r.budget_reason = "the next decade, " + std::to_string(next) + " steps, would take about " +
                        fixed(predicted, "%.3g") + " s of CPU (10 times this run's), past " +
                        fixed(spec.cpu_max_s, "%.6g") + " s (--horizon-cpu-max)";
      break;
    }
    EarlierRun e;
    e.steps = r.steps, e.t_end = r.t_end, e.status = r.status, e.cpu_s = r.cpu_s, e.wall_s = r.wall_s;
    e.energy_error = largest_of(r.energy_error);
    e.energy_error_on_group = largest_of(r.energy_error_on_group);
    e.rotation_defect = largest_of(r.rotation_defect);
    e.energy_class = r.energy_fit.growth_class;
    e.energy_on_group_class = r.energy_on_group_fit.growth_class;
    e.defect_class = r.defect_fit.growth_class;
    earlier.push_back(e);
    decade.steps = next;
    r = horizon_run(problem, m, decade);
  }
  r.study_steps = spec.steps;
  r.earlier = std::move(earlier);
  return r;
}

void check_horizon(const HorizonSpec& spec) {
  if (!spec.enabled) return;
  if (!(spec.steps >= 1000 && spec.steps <= 100'000'000))
    throw InputError("expected a whole number of steps from 1000 to 100000000, got " + std::to_string(spec.steps),
                     "horizon-steps");
  if (!(spec.h > 0.0 && std::isfinite(spec.h))) throw InputError("the step must be a finite number > 0", "horizon-h");
  if (spec.steps_max != 0 && !(spec.steps_max >= spec.steps && spec.steps_max <= 100'000'000))
    throw InputError("expected the most steps from --horizon-steps (" + std::to_string(spec.steps) +
                         ") to 100000000, got " + std::to_string(spec.steps_max),
                     "horizon-steps-max");
  if (!(spec.cpu_max_s > 0.0 && std::isfinite(spec.cpu_max_s)))
    throw InputError("the CPU seconds of a further decade must be a finite number > 0", "horizon-cpu-max");
  if (spec.samples_per_decade < 1 || spec.dense_outputs < 1 || spec.window_outputs < 1)
    throw InputError("samples per decade, dense outputs and window outputs must be > 0", "horizon");
  // a class needs three decades of t (bench/lib/growth_class.hpp)
  if (spec.fit_decades < 3) throw InputError("a class needs at least 3 decades of t", "horizon");
  if (spec.scenes.empty()) throw InputError("the horizon study needs at least one scene", "horizon-scenes");
  if (spec.integrators.empty())
    throw InputError("the horizon study needs at least one integrator", "horizon-integrators");
  for (const std::string& name : spec.integrators)
    if (find_integrator(name).adaptive())
      throw InputError("'" + name + "' is adaptive: the horizon study takes fixed steps", "horizon-integrators");
  for (const std::string& scene : spec.scenes) (void)load_scene(scene);
}

namespace {

// Decimal digits with a fraction or an exponent ("1e6", "2.5", "1e-9"),
// no leading sign or space: strtod alone also takes spaces, a sign,
// hexadecimal and "inf" ("0x3E8" would be 1000 steps).
bool plain_decimal(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789.") != 0 &&
         text.find_first_not_of("0123456789.eE+-") == std::string::npos;
}

}  // namespace

long parse_horizon_steps(const std::string& text, const std::string& key) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (!plain_decimal(text) || end != text.c_str() + text.size() || !(v >= 1000.0 && v <= 1e8) || v != std::floor(v))
    throw InputError(
        "expected a whole number of steps from 1000 to 1e8 (e.g. 100000 or 1e6), got '" + valid_utf8(text) + "'", key);
  return static_cast<long>(v);
}

double parse_horizon_cpu_max(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (!plain_decimal(text) || end != text.c_str() + text.size() || !(v > 0.0 && std::isfinite(v)))
    throw InputError("expected seconds, a finite number > 0 (e.g. 600), got '" + valid_utf8(text) + "'",
                     "horizon-cpu-max");
  return v;
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
    // the study's runs go on decade by decade while undecided; a price run
    // is one run at k h, no class read from it
    const Problem& problem = problems[in_block / hs.integrators.size()];
    HorizonRecord r = coarsening == 1 ? horizon_decades(problem, find_integrator(name), run_spec)
                                      : horizon_run(problem, find_integrator(name), run_spec);
    r.index = index;
    r.coarsening = coarsening;
    std::string invariants;
    for (const InvariantSeries& s : r.invariants) invariants += ", " + s.name + " " + class_text(s.fit);
    std::string decades;
    for (const EarlierRun& e : r.earlier) decades += std::to_string(e.steps) + " steps undecided, ";
    if (!r.earlier.empty()) decades = " (" + decades + "then " + std::to_string(r.steps) + ")";
    const std::lock_guard<std::mutex> hold(report_lock);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string at = coarsening == 1 ? "" : " at " + std::to_string(coarsening) + " h";
    progress("horizon: " + name + " on " + r.scene + at + ": " + std::string(status_name(r.status)) + decades +
             ", energy " + class_text(r.energy_on_group_fit) + ", rotation defect " + class_text(r.defect_fit) +
             invariants + (r.budget_reason.empty() ? "" : "; undecided: " + r.budget_reason) + ", " +
             fixed(r.cpu_s, "%.2f") + " s CPU (" + progress_line("horizon", ++done, mine.size(), elapsed) + ")");
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
    json same = {{"energy_error", nullptr}, {"rotation_defect", nullptr}, {"energy_error_on_group", nullptr}};
    for (const char* key : {"energy_error", "rotation_defect", "energy_error_on_group"})
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

namespace {

json earlier_json(const std::vector<EarlierRun>& earlier) {
  json out = json::array();
  for (const EarlierRun& e : earlier)
    out.push_back({{"steps", e.steps},
                   {"t_end", e.t_end},
                   {"status", std::string(status_name(e.status))},
                   {"cpu_s", e.cpu_s},
                   {"wall_s", e.wall_s},
                   {"largest",
                    {{"energy_error", number(e.energy_error)},
                     {"energy_error_on_group", number(e.energy_error_on_group)},
                     {"rotation_defect", number(e.rotation_defect)}}},
                   {"class",
                    {{"energy_error", class_json(e.energy_class)},
                     {"energy_error_on_group", class_json(e.energy_on_group_class)},
                     {"rotation_defect", class_json(e.defect_class)}}}});
  return out;
}

}  // namespace

json horizon_json(const HorizonResults& results) {
  json runs = json::array();
  for (const HorizonRecord& r : results.runs) {
    json invariants = json::array();
    for (const InvariantSeries& s : r.invariants) {
      json error = json::array();
      for (const double e : s.error) error.push_back(number(e));
      invariants.push_back(
          {{"name", s.name}, {"kind", std::string(kind_name(s.kind))}, {"error", error}, {"fit", fit_json(s.fit)}});
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
                    {"study_steps", r.study_steps},
                    {"earlier_runs", earlier_json(r.earlier)},
                    {"budget_ran_out", !r.budget_reason.empty()},
                    {"budget_reason", r.budget_reason.empty() ? json(nullptr) : json(r.budget_reason)},
                    {"t_end", r.t_end},
                    {"status", std::string(status_name(r.status))},
                    {"message", r.message},
                    {"stop_time", r.stop_time},
                    {"steps", r.cost.steps},
                    {"rhs_evals", r.cost.rhs_evals},
                    {"rhs_equivalents", r.cost.rhs_equivalents()},
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
                    {"energy_error_on_group", r.energy_error_on_group},
                    {"fit",
                     {{"energy_error", fit_json(r.energy_fit)},
                      {"rotation_defect", fit_json(r.defect_fit)},
                      {"energy_error_on_group", fit_json(r.energy_on_group_fit)}}},
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
          {"steps_max", std::max(s.steps, s.steps_max)},
          {"cpu_max_s", s.cpu_max_s},
          {"samples_per_decade", s.samples_per_decade},
          {"fit_decades", s.fit_decades},
          {"dense_outputs", s.dense_outputs},
          {"window_outputs", s.window_outputs},
          {"asymptotic_spread", s.asymptotic_spread},
          {"slope_resolution", GrowthRules{}.resolution},
          {"class_band", GrowthRules{}.band},
          {"exponential_slope", GrowthRules{}.exponential_slope},
          {"coarsenings", price_coarsenings(s)},
          {"same_series_rise", kSameSeriesRise}};
}

}  // namespace rb

// rollbench: the command-line front end. Library code throws; this file
// turns errors into messages and exit codes (0 ok, 2 bad input, 3 a run that
// stopped early).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <tuple>

#include "bench/lib/drift.hpp"
#include "bench/lib/output_file.hpp"
#include "bench/lib/reference.hpp"
#include "bench/lib/report.hpp"
#include "bench/lib/reversibility.hpp"
#include "bench/lib/run_on_threads.hpp"
#include "bench/lib/score.hpp"
#include "bench/lib/score_peers.hpp"
#include "bench/lib/stepper_option.hpp"
#include "bench/lib/tableau_option.hpp"
#include "bench/lib/trajectory_csv.hpp"
#include "integrators/controllers/controller.hpp"
#include "integrators/driver.hpp"
#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/input_file.hpp"
#include "problems/scene.hpp"
#include "problems/whole_number.hpp"

namespace {

std::string declared_order_text(const rb::MethodInfo& m) {
  std::string order = std::to_string(m.declared_order);
  if (m.embedded_order > 0) order += "(" + std::to_string(m.embedded_order) + ")";
  return order;
}

// The registry as the Markdown table docs/integrators.md carries
// (scripts/method_table.py writes it there; tests/docs checks it is current).
int run_list_markdown() {
  std::printf("| name | family | order | steps | description |\n| --- | --- | --- | --- | --- |\n");
  for (const auto& integrator : rb::registry()) {
    const rb::MethodInfo m = integrator->info();
    std::string description;
    for (const char c : m.description) description += c == '|' ? std::string("\\|") : std::string(1, c);
    std::printf("| %s | `%s` | %s | %s | %s |\n", m.name.c_str(), m.family.c_str(), declared_order_text(m).c_str(),
                m.adaptive ? "adaptive" : "fixed", description.c_str());
  }
  return 0;
}

int run_list(bool markdown) {
  if (markdown) return run_list_markdown();
  std::printf("integrators (name, family, declared order with the embedded one in parentheses, adaptive):\n");
  // columns as wide as their widest entry, so a long family name never shifts the row
  int name_width = 0, family_width = 0;
  for (const auto& integrator : rb::registry()) {
    name_width = std::max(name_width, static_cast<int>(integrator->info().name.size()));
    family_width = std::max(family_width, static_cast<int>(integrator->info().family.size()));
  }
  for (const auto& integrator : rb::registry()) {
    const rb::MethodInfo m = integrator->info();
    std::printf("  %-*s %-*s %5s  %-8s %s\n", name_width, m.name.c_str(), family_width, m.family.c_str(),
                declared_order_text(m).c_str(), m.adaptive ? "adaptive" : "fixed", m.description.c_str());
  }
  std::printf("\nscenes (in %s):\n", RB_SCENE_DIR);
  for (const std::string& name : rb::shipped_scene_names()) {
    const rb::Scene scene = rb::read_shipped_scene(name);
    std::printf("  %-18s %s\n", name.c_str(), scene.description.c_str());
  }
  return 0;
}

// A --t-end where it is given: a finite number > 0, and within a scene's
// t_end range (problems/scene.hpp: a subnormal end time underflows the steps).
void check_t_end(double t_end) {
  if (!(t_end > 0.0 && std::isfinite(t_end))) throw rb::InputError("the end time must be a finite number > 0", "t-end");
  if (!(t_end >= rb::kMinTEnd && t_end <= rb::kMaxTEnd))
    throw rb::InputError("the end time must be from 1e-6 to 1e7 (seconds), as a scene's t_end", "t-end");
}

struct TrajectoryArgs {
  std::string scene, integrator, out, controller;
  // NaN: not given, the default applies; anything given is checked
  double h = 0.0, rtol = 0.0, atol = 0.0, dt_out = std::nan(""), t_end = std::nan("");
};

int run_trajectory(const TrajectoryArgs& a) {
  const rb::Scene scene = rb::load_scene(a.scene);
  const rb::Problem problem = rb::make_problem(scene);
  const rb::Integrator& integrator = rb::find_integrator(a.integrator);
  rb::RunOptions options;
  if (!std::isnan(a.t_end)) check_t_end(a.t_end);
  if (!std::isnan(a.dt_out) && !(a.dt_out > 0.0 && std::isfinite(a.dt_out)))
    throw rb::InputError("the output spacing must be a finite number > 0", "dt-out");
  if (!integrator.adaptive() && !std::isfinite(a.h)) throw rb::InputError("the step must be a finite number > 0", "h");
  options.t_end = std::isnan(a.t_end) ? problem.t_end() : a.t_end;
  if (!integrator.adaptive() && !(a.h > 0.0))
    throw rb::InputError("'" + integrator.name() + "' is a fixed-step method and needs --h > 0", "h");
  options.h = a.h;
  if (!a.controller.empty()) options.controller = &rb::filter_controller(a.controller);  // refuses unknown names
  // the tolerances, checked before a file is written: an adaptive method
  // needs them; a fixed-step one takes them when given (GSL's implicit
  // steppers' Newton tolerance)
  if (integrator.adaptive() || a.rtol != 0.0 || a.atol != 0.0) options.tolerances = rb::Tolerances(a.rtol, a.atol);
  // and the initial step, as the run checks it
  if (integrator.adaptive()) (void)rb::tolerances_of(options);
  // a fixed-step method lands on every output, so outputs closer than h
  // would silently shorten its step: that is refused, not done
  if (!integrator.adaptive() && a.dt_out < a.h)
    throw rb::InputError("the output spacing must not be smaller than the step h = " + std::to_string(a.h), "dt-out");
  const double dt_out = std::isnan(a.dt_out) ? std::max(0.01, a.h) : a.dt_out;
  options.output_times = rb::equally_spaced_outputs(dt_out, options.t_end);

  // the CSV replaces a.out only once it is whole (bench/lib/output_file.hpp)
  rb::OutputFile out(a.out, "out", rb::IfLost::keep_elsewhere);
  const rb::RunResult run = integrator.integrate(problem, options);
  rb::write_trajectory_csv(out.stream(), problem, run.output);
  out.commit();

  // a summary on standard output: how the run went and what it cost
  const rb::Drift drift = rb::largest_drift(problem, run.output);
  std::printf("%s on %s: %s at t = %.6g (%zu rows in %s)\n", integrator.name().c_str(), scene.name.c_str(),
              std::string(rb::status_name(run.status)).c_str(), run.stop_time, run.output.t.size() + 1, a.out.c_str());
  std::printf("  steps %ld, rejected %ld, rhs evals %ld, controller %s\n", run.cost.steps, run.cost.rejected,
              run.cost.rhs_evals, rb::controller_of(integrator.controller(), options).c_str());
  std::printf("  max |energy error| %.3e (at the nearest rotation %.3e), max rotation defect %.3e\n", drift.energy,
              drift.energy_on_group, drift.rotation_defect);
  if (run.status != rb::Status::ok) {
    std::fprintf(stderr, "rollbench: run stopped early at t = %.17g: %s: %s\n", run.stop_time,
                 std::string(rb::status_name(run.status)).c_str(), run.message.c_str());
  }
  return rb::exit_code_of(run.status);
}

struct ReversibilityArgs {
  std::string scene, integrators;
  double h = std::nan(""), tol = std::nan(""), t_end = std::nan("");
};

// Each method's reversibility defect on one scene (bench/lib/reversibility.hpp).
int run_reversibility(const ReversibilityArgs& a) {
  const rb::Scene scene = rb::load_scene(a.scene);
  if (!std::isnan(a.t_end)) check_t_end(a.t_end);
  if (!std::isnan(a.h) && !(a.h > 0.0 && std::isfinite(a.h)))
    throw rb::InputError("the step must be a finite number > 0", "h");
  if (!std::isnan(a.tol) && !(a.tol > 0.0 && std::isfinite(a.tol)))
    throw rb::InputError("the tolerance must be a finite number > 0", "tol");
  const rb::Tolerances tolerances = std::isnan(a.tol) ? rb::Tolerances() : rb::Tolerances(a.tol, a.tol);
  std::vector<const rb::Integrator*> methods;
  std::stringstream names(a.integrators);
  for (std::string name; std::getline(names, name, ',');) {
    const rb::Integrator& m = rb::find_integrator(name);
    if (!m.adaptive() && std::isnan(a.h)) throw rb::InputError("'" + name + "' is a fixed-step method: give --h", "h");
    if (m.adaptive() && std::isnan(a.tol)) throw rb::InputError("'" + name + "' is adaptive: give --tol", "tol");
    methods.push_back(&m);
  }
  if (methods.empty()) throw rb::InputError("name at least one method", "integrators");
  const rb::Problem problem = rb::make_problem(scene);
  rb::RunOptions options;
  options.t_end = std::isnan(a.t_end) ? problem.t_end() : a.t_end;
  std::printf("reversibility defect on %s over [0, %g] and back (contact / r, rotation rad, momentum relative):\n",
              scene.name.c_str(), options.t_end);
  std::printf("  %-28s %10s %10s %10s %10s %10s\n", "integrator", "steps", "contact", "rotation", "momentum", "worst");
  for (const rb::Integrator* m : methods) {
    rb::RunOptions o = options;
    if (m->adaptive()) o.tolerances = tolerances;
    else o.h = a.h;
    const rb::ReversibilityDefect d = rb::reversibility_defect(*m, problem, o);
    if (d.status != rb::Status::ok) {
      std::printf("  %-28s %10ld %s: %s\n", m->name().c_str(), d.steps, std::string(rb::status_name(d.status)).c_str(),
                  d.message.c_str());
      continue;
    }
    std::printf("  %-28s %10ld %10.3e %10.3e %10.3e %10.3e\n", m->name().c_str(), d.steps, d.contact, d.rotation,
                d.momentum, d.worst());
  }
  return 0;
}

struct LandscapeArgs {
  std::string scene, grid, domain, out;
};

// Exactly `count` finite numbers separated by commas; InputError naming the option otherwise.
std::vector<double> parse_exact_numbers(const std::string& text, std::size_t count, const std::string& option,
                                        const std::string& expected) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      throw rb::InputError("expected " + expected + ", got '" + text + "'", option);
    values.push_back(v);
  }
  if (values.size() != count || (!text.empty() && text.back() == ','))
    throw rb::InputError("expected " + expected + ", got '" + text + "'", option);
  return values;
}

// z = f(x, y) of a scene on an NX x NY grid, as CSV "x,y,z" with x running
// fastest: the analysis draws the landscapes from these values, so no
// second formula parser is needed there.
int run_landscape(const LandscapeArgs& a) {
  constexpr int max_points = 2048;  // per axis: plenty for a picture, bounded memory and time
  const std::vector<double> grid = parse_exact_numbers(a.grid, 2, "grid", "NX,NY (two integers)");
  for (double n : grid)
    if (n != std::floor(n) || n < 2 || n > max_points)
      throw rb::InputError(
          "each of NX,NY must be an integer from 2 to " + std::to_string(max_points) + ", got '" + a.grid + "'",
          "grid");
  const rb::Scene scene = rb::load_scene(a.scene);
  rb::Domain box = scene.domain;
  if (!a.domain.empty()) {
    const std::vector<double> d = parse_exact_numbers(a.domain, 4, "domain", "xmin,xmax,ymin,ymax");
    box = {d[0], d[1], d[2], d[3]};
  } else if (!scene.has_domain) {
    throw rb::InputError("scene '" + scene.name + "' has no domain: give one as xmin,xmax,ymin,ymax", "domain");
  }
  if (!(box.xmin < box.xmax && box.ymin < box.ymax))
    throw rb::InputError("expected xmin < xmax and ymin < ymax", "domain");
  const rb::RollingBall model = rb::make_model(scene);
  std::optional<rb::OutputFile> file;
  if (!a.out.empty()) file.emplace(a.out, "out");
  std::ostream& out = file ? file->stream() : std::cout;
  const int nx = static_cast<int>(grid[0]), ny = static_cast<int>(grid[1]);
  out << "x,y,z\n";
  char line[96];
  for (int j = 0; j < ny; ++j) {
    const double y = box.ymin + (box.ymax - box.ymin) * j / (ny - 1);
    for (int i = 0; i < nx; ++i) {
      const double x = box.xmin + (box.xmax - box.xmin) * i / (nx - 1);
      // NaN where the formula is undefined (sqrt of a negative, ...): the plot masks it
      std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", x, y, model.landscape().height(x, y));
      out << line;
    }
  }
  if (file) file->commit();
  out.flush();
  if (!out) throw rb::InputError("could not write the grid", "out");
  return 0;
}

// timed repeats per run: enough for any median, and a typo's 10^9 is refused
constexpr long long kMaxRepeats = 1000;

struct RunArgs {
  std::string preset, scenes, integrators, hs, tols, out, cache, controller, regime;
  // not given: the preset's (shard: the whole sweep); read strictly (problems/whole_number.hpp)
  std::optional<std::string> repeats, jobs, shard;
  double dt_out = std::nan("");  // NaN: not given
  std::optional<double> t_end;   // given: checked, even "nan"
  bool no_stability = false;
  // --stability-horizons: the study's horizons; enables the study
  std::optional<std::string> stability_horizons;
  bool no_finer_steps = false;  // keep the step ladder as given (a sharded sweep's ladder)
  // the horizon study (bench/lib/horizon.hpp): --horizon-steps enables it
  std::string horizon_steps, horizon_scenes, horizon_integrators;
  // the budget of the decades after the first
  std::string horizon_steps_max, horizon_cpu_max;
  bool no_horizon = false;
};

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) names.push_back(item);
  return names;
}

// split_names' inverse, for help texts.
std::string join_names(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ",") + name;
  return text;
}

// Text from outside is made valid UTF-8 where it enters (problems/utf8.hpp);
// the dump replaces what might still slip through, so that no report is
// lost to a strict dump. The file replaces path only once it is whole.
std::string json_text(const nlohmann::json& j) {
  return j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + '\n';
}

// The output --out names, opened before any work, so that an unwritable
// place or a folder behind another user's link is refused before a
// reference or run (bench/lib/output_file.hpp); none for "" or "-"
// (standard output). What cannot be written at the end is kept elsewhere,
// and the error says where.
std::optional<rb::OutputFile> open_output(const std::string& path) {
  if (path.empty() || path == "-") return std::nullopt;
  return std::optional<rb::OutputFile>(std::in_place, path, "out", rb::IfLost::keep_elsewhere);
}

// The JSON into the output open_output opened; none: standard output.
void write_json(const nlohmann::json& j, std::optional<rb::OutputFile>& file) {
  if (!file) {
    std::fputs(json_text(j).c_str(), stdout);
    return;
  }
  file->stream() << json_text(j);
  file->commit();
}

// --horizon-steps N enables the study (the default preset's scenes and
// methods unless named); every name is checked before any reference.
void apply_horizon_options(const RunArgs& a, rb::HorizonSpec& h) {
  const bool given = !a.horizon_steps.empty() || !a.horizon_scenes.empty() || !a.horizon_integrators.empty() ||
                     !a.horizon_steps_max.empty() || !a.horizon_cpu_max.empty();
  if (a.no_horizon && given)
    throw rb::InputError(
        "--no-horizon cannot go with --horizon-steps, --horizon-steps-max, --horizon-cpu-max, --horizon-scenes or "
        "--horizon-integrators",
        "no-horizon");
  if (a.no_horizon) h.enabled = false;
  if (!given) return rb::check_horizon(h);
  if (!h.enabled) h = rb::preset("default").horizon;
  if (!a.horizon_steps.empty()) h.steps = rb::parse_horizon_steps(a.horizon_steps);
  if (!a.horizon_steps_max.empty()) h.steps_max = rb::parse_horizon_steps(a.horizon_steps_max, "horizon-steps-max");
  if (!a.horizon_cpu_max.empty()) h.cpu_max_s = rb::parse_horizon_cpu_max(a.horizon_cpu_max);
  if (!a.horizon_scenes.empty()) h.scenes = split_names(a.horizon_scenes);
  if (!a.horizon_integrators.empty()) h.integrators = split_names(a.horizon_integrators);
  rb::check_horizon(h);
}

int run_sweep_command(const RunArgs& a, const std::vector<std::string>& tableau_methods) {
  // without --preset: the default preset's sweep, not its stability study
  // (which has its own scenes and methods, and minutes of runs)
  // --regime alone is the regime preset with that grid
  if (!a.regime.empty() && !a.preset.empty() && a.preset != "regime")
    throw rb::InputError("the grid goes with --preset regime (or no preset), not '" + a.preset + "'", "regime");
  rb::SweepSpec spec = rb::preset(a.preset.empty() ? (a.regime.empty() ? "default" : "regime") : a.preset);
  if (a.preset.empty() && a.regime.empty()) {
    spec.preset = "custom";
    spec.stability.enabled = false;
    spec.horizon.enabled = false;
  }
  if (!a.regime.empty()) spec.regime = rb::parse_regime_grid(a.regime, *spec.regime);
  if (spec.regime && !a.scenes.empty())
    throw rb::InputError("the regime study generates its scenes from its grid (--regime): give no --scenes", "scenes");
  if (!a.scenes.empty()) spec.scenes = split_names(a.scenes);
  if (!a.integrators.empty()) spec.integrators = split_names(a.integrators);
  spec.integrators = rb::with_tableau_methods(spec.integrators, !a.integrators.empty(), tableau_methods);
  // every name checked before a reference is computed (minutes on a long scene)
  for (const std::string& name : spec.integrators) (void)rb::find_integrator(name);
  if (!a.hs.empty()) spec.hs = rb::parse_number_list(a.hs, "h");
  if (!a.tols.empty()) spec.tols = rb::parse_number_list(a.tols, "tol");
  if (!a.controller.empty()) spec.controller = &rb::filter_controller(a.controller);  // refuses unknown names
  if (a.repeats) spec.repeats = static_cast<int>(rb::parse_whole_number(*a.repeats, 0, kMaxRepeats, "repeats"));
  if (a.jobs) {
    spec.jobs = static_cast<int>(rb::parse_whole_number(*a.jobs, 1, rb::kMaxJobs, "jobs"));
    // the report keeps the jobs asked for (shards of one sweep on machines
    // of other sizes still merge); the runs use at most one thread per core
    if (const int threads = rb::threads_for(spec.jobs); threads < spec.jobs)
      std::fprintf(stderr, "rollbench: note: --jobs %d is more than the %d cores here: the runs use %d threads\n",
                   spec.jobs, threads, threads);
  }
  if (a.no_stability) spec.stability.enabled = false;
  if (a.stability_horizons) {
    if (a.no_stability)
      throw rb::InputError("--no-stability cannot go with --stability-horizons", "stability-horizons");
    const std::vector<double> horizons = rb::parse_stability_horizons(*a.stability_horizons, "stability-horizons");
    // without a preset's study: the default preset's scenes and methods
    if (!spec.stability.enabled) spec.stability = rb::preset("default").stability;
    spec.stability.horizons = horizons;
  }
  if (a.no_finer_steps) spec.extend_ladders = false;
  for (const std::string& name : spec.stability.integrators)
    if (spec.stability.enabled) (void)rb::find_integrator(name);
  apply_horizon_options(a, spec.horizon);
  if (!std::isnan(a.dt_out)) {
    if (!(a.dt_out > 0.0 && std::isfinite(a.dt_out)))
      throw rb::InputError("the output spacing must be a finite number > 0", "dt-out");
    spec.dt_out = a.dt_out;
  }
  if (a.t_end) {
    check_t_end(*a.t_end);
    spec.t_end = *a.t_end;
  }
  spec.cache_dir = a.cache;
  if (a.shard) std::tie(spec.shard_index, spec.shard_count) = rb::parse_shard(*a.shard);
  // the report's place and the cache folder, before any reference or run
  std::optional<rb::OutputFile> report_file = open_output(a.out);
  rb::check_cache_folder(a.cache);
  auto progress = [](const std::string& line) { std::fprintf(stderr, "rollbench: %s\n", line.c_str()); };
  progress("preparing scenes and references");
  const std::vector<rb::SweepScene> scenes = rb::prepare_scenes(spec, true, progress);
  for (const rb::SweepScene& s : scenes) {
    char error[32];
    std::snprintf(error, sizeof error, "%.2e", s.reference.error);
    progress("reference of " + s.scene.name + ": " + s.reference.kind + " (" + s.reference.method + "), own error " +
             error + (s.reference.from_cache ? " (cached)" : "") + s.reference.message);
  }
  const std::vector<rb::RunRecord> runs = rb::run_sweep(spec, scenes, progress);
  const rb::StabilityResults stability = rb::run_stability(spec, progress);
  const rb::HorizonResults horizon = rb::run_horizon(spec, progress);
  const rb::Report report = rb::make_report(spec, scenes, runs, stability, horizon);
  write_json(rb::to_json(report), report_file);
  std::printf("%s", rb::summary_table(report).c_str());
  std::printf("report written to %s\n", a.out.c_str());
  return 0;
}

struct ScoreArgs {
  std::string scene, csv, out, cache, peers, into;
  std::optional<double> t_end, dt_out;
};

// A trajectory from another program scored against the suite's reference.
int run_score(const ScoreArgs& a) {
  if (!a.peers.empty()) {  // another program's solves as report runs
    if (!a.scene.empty() || a.t_end || a.dt_out)
      throw rb::InputError("takes no scene, trajectory, --t-end or --dt-out: the peer file names them", "peers");
    if (a.out.empty()) throw rb::InputError("the report needs --out FILE", "out");
    std::optional<rb::OutputFile> report_file = open_output(a.out);  // before any reference
    rb::check_cache_folder(a.cache);
    const nlohmann::json report = rb::score_peers(a.peers, a.into, a.cache);
    write_json(report, report_file);
    std::printf("%s", rb::summary_table(rb::report_from_json(report, a.out)).c_str());
    std::printf("report with the runs of %s written to %s\n", a.peers.c_str(), a.out.c_str());
    return 0;
  }
  if (!a.into.empty()) throw rb::InputError("goes with --peers", "into");
  if (a.scene.empty() || a.csv.empty())
    throw rb::InputError("expected SCENE TRAJECTORY.csv, or --peers PEERS.json", "score");
  // a regular file of at most 256 MiB, read before the scene's reference is computed
  std::istringstream csv(rb::read_input_file(a.csv, rb::kTrajectoryInput, "trajectory"));
  rb::ScoreOptions options;
  options.cache_dir = a.cache;
  // given: a finite number > 0 (0 in ScoreOptions means "the default")
  if (a.t_end) check_t_end(*a.t_end);
  if (a.dt_out && !(*a.dt_out > 0.0 && std::isfinite(*a.dt_out)))
    throw rb::InputError("the output spacing must be a finite number > 0", "dt-out");
  options.t_end = a.t_end.value_or(0.0);
  options.dt_out = a.dt_out.value_or(0.0);
  std::optional<rb::OutputFile> score_file = open_output(a.out);  // before the reference
  rb::check_cache_folder(a.cache);
  const nlohmann::json score = rb::score_trajectory(a.scene, csv, a.csv, options);
  if (a.out.empty()) {
    std::printf("%s", json_text(score).c_str());
  } else {
    write_json(score, score_file);
    std::printf("score of %s on %s written to %s\n", a.csv.c_str(), a.scene.c_str(), a.out.c_str());
  }
  std::fprintf(stderr, "rollbench: timing is the user's: score measures accuracy and drift only (status %s)\n",
               score["status"].get<std::string>().c_str());
  return 0;
}

int run_merge(const std::vector<std::string>& inputs, const std::string& out) {
  std::optional<rb::OutputFile> merged = open_output(out);  // before the reports are read
  std::vector<rb::Report> shards;                           // each file read once, named in what it lacks
  for (const std::string& path : inputs) shards.push_back(rb::report_from_json(rb::read_report(path), path));
  write_json(rb::to_json(rb::merge_named_reports(shards, inputs)), merged);
  std::printf("merged %zu reports into %s\n", inputs.size(), out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rollbench: integrators compared on a ball rolling on z = f(x, y)"};
  app.require_subcommand(1);
  // --tableau FILE, repeatable, on list, trajectory and run: one file per occurrence
  std::vector<std::string> tableau_files;
  auto add_tableau_option = [&](CLI::App* command) {
    command
        ->add_option("--tableau", tableau_files,
                     "a Butcher tableau JSON file: adds rk-<name>, rkmk-<name> (repeatable)")
        ->allow_extra_args(false);
  };

  CLI::App* list = app.add_subcommand("list", "list the registered integrators and the shipped scenes");
  // --stepper PATH.so (repeatable): a stepper library (integrators/plugin/rollbench_stepper.h)
  std::vector<std::string> steppers;
  const char* stepper_help = "a stepper library built against integrators/plugin/rollbench_stepper.h (repeatable)";
  // how plug-in runs are isolated (integrators/steppers/isolated_run.hpp)
  std::string stepper_isolation;
  double stepper_timeout = std::nan("");  // NaN: not given
  auto add_isolation_options = [&](CLI::App* command) {
    command->add_option("--stepper-isolation", stepper_isolation,
                        "process (default: each --stepper run in a child process; a crash or hang is a status) or "
                        "none (in-process)");
    command->add_option("--stepper-timeout", stepper_timeout,
                        "wall-clock limit in seconds of one isolated --stepper run (default 300); past it the run "
                        "is killed: status timeout");
  };
  bool list_markdown = false;
  list->add_flag("--markdown", list_markdown,
                 "the integrators alone, as the Markdown table of docs/integrators.md (scripts/method_table.py)");
  list->add_option("--stepper", steppers, stepper_help);
  add_tableau_option(list);

  const char* controller_help =
      "step-size controller of the adaptive methods that take one: i, pi or pid (default: each method's own)";

  TrajectoryArgs traj;
  CLI::App* trajectory = app.add_subcommand("trajectory", "integrate one scene with one method and write a CSV");
  trajectory->add_option("scene", traj.scene, "a shipped scene's name or a scene JSON file")->required();
  trajectory->add_option("--integrator", traj.integrator, "registry name (see `rollbench list`)")->required();
  trajectory->add_option("--h", traj.h, "step size of a fixed-step method");
  trajectory->add_option("--rtol", traj.rtol, "relative tolerance of an adaptive method");
  trajectory->add_option("--atol", traj.atol, "absolute tolerance of an adaptive method");
  trajectory->add_option("--dt-out", traj.dt_out,
                         "spacing of the output rows, >= h (default: the larger of 0.01 and h)");
  trajectory->add_option("--t-end", traj.t_end, "end time (default: the scene's t_end)");
  trajectory->add_option("--controller", traj.controller, controller_help);
  trajectory->add_option("--out", traj.out, "the CSV file to write")->required();
  trajectory->add_option("--stepper", steppers, stepper_help);
  add_isolation_options(trajectory);
  add_tableau_option(trajectory);

  LandscapeArgs land;
  CLI::App* landscape = app.add_subcommand("landscape", "print z = f(x, y) of a scene on a grid (CSV x,y,z)");
  landscape->add_option("scene", land.scene, "a shipped scene's name or a scene JSON file")->required();
  landscape->add_option("--grid", land.grid, "NX,NY: points along x and y (2 to 2048 each)")->required();
  landscape->add_option("--domain", land.domain, "xmin,xmax,ymin,ymax (default: the scene's domain)");
  landscape->add_option("--out", land.out, "write the CSV here instead of standard output");

  ReversibilityArgs rev;
  CLI::App* reversibility = app.add_subcommand(
      "reversibility", "each method's reversibility defect: forward to t_end, v -> -v, forward again, v -> -v");
  reversibility->add_option("scene", rev.scene, "a shipped scene's name or a scene JSON file")->required();
  reversibility->add_option("--integrators", rev.integrators, "comma-separated registry names")->required();
  reversibility->add_option("--h", rev.h, "step size of the fixed-step methods");
  reversibility->add_option("--tol", rev.tol, "tolerance (rtol = atol) of the adaptive methods");
  reversibility->add_option("--t-end", rev.t_end, "end time of each leg (default: the scene's t_end)");
  reversibility->add_option("--stepper", steppers, stepper_help);
  add_tableau_option(reversibility);

  RunArgs run;
  CLI::App* run_cmd = app.add_subcommand("run", "sweep scenes x integrators x h or tolerances into a JSON report");
  run_cmd->add_option("--preset", run.preset,
                      "quick (CI), default (the main job), full (a study) or regime (the regime map over "
                      "generated scenes); without it, the default preset's sweep without its stability study");
  run_cmd->add_option("--scenes", run.scenes, "comma-separated shipped scene names or JSON paths");
  run_cmd->add_option("--regime", run.regime,
                      "the regime study's grid: default, full, or axes inertia=1,3;spin=0.1,5,50;"
                      "roughness=0,0.3;t_end=1;bowl=0.1,0.5,2;speed=0.1,0.5 (those not given: the regime "
                      "preset's), and held_out=none to leave out the held-out scenes");
  run_cmd->add_option("--integrators", run.integrators, "comma-separated registry names");
  run_cmd->add_option("--h", run.hs, "step sizes, e.g. 0.1,0.05 or 2^-3..2^-8");
  run_cmd->add_option("--tol", run.tols, "tolerances (rtol = atol) of adaptive methods, e.g. 1e-4,1e-8");
  run_cmd->add_option("--controller", run.controller, controller_help);
  run_cmd->add_option("--dt-out", run.dt_out,
                      "record the state every dt-out in the timed runs and measure error_max there "
                      "(default: the timed runs record t_end only; error_max is measured every 0.25 in untimed runs)");
  run_cmd->add_option("--t-end", run.t_end,
                      "end every scene at the smaller of this and its own t_end (default: each scene's t_end; the "
                      "quick preset's: 2)");
  run_cmd->add_option("--repeats", run.repeats,
                      "timed repeats per run (default: the preset's; quick 2, default 3, full 7, regime 3), 0 to "
                      "1000");
  run_cmd->add_option("--jobs", run.jobs,
                      "threads for the accuracy runs (default: 2), 1 to 1024; at most one per core is used");
  run_cmd->add_option("--shard", run.shard,
                      "i/n with 0 <= i < n <= 100000: run one slice of the sweep (join with `rollbench merge`)");
  run_cmd->add_option("--cache", run.cache, "directory for cached reference solutions");
  run_cmd->add_flag("--no-stability", run.no_stability, "skip the stability study of the preset");
  run_cmd->add_option("--stability-horizons", run.stability_horizons,
                      "the stability study's horizons in s, increasing, e.g. 10,100,1000 (the default): the "
                      "drift-limited step and the blow-up step at each; runs the study (the default preset's "
                      "scenes) where the preset has none");
  run_cmd->add_flag("--no-finer-steps", run.no_finer_steps,
                    "keep the step ladder as given: no finer steps for pre-asymptotic order fits");
  run_cmd->add_option("--horizon-steps", run.horizon_steps,
                      "run the horizon study with this many fixed steps per run, e.g. 1e5 or 1e6 (the default "
                      "preset's: 1e6; full: 1e7)");
  run_cmd->add_option("--horizon-steps-max", run.horizon_steps_max,
                      "where a horizon run's growth class is undecided, run it again at 10 times the steps up to "
                      "this many, e.g. 1e7 (default: --horizon-steps, no further decade)");
  run_cmd->add_option("--horizon-cpu-max", run.horizon_cpu_max,
                      "seconds of CPU a further decade's run may take, predicted as 10 times the run before it "
                      "(default: 600)");
  const rb::HorizonSpec study = rb::preset("default").horizon;
  run_cmd->add_option("--horizon-scenes", run.horizon_scenes,
                      "the horizon study's scenes (default: " + join_names(study.scenes) + ")");
  run_cmd->add_option("--horizon-integrators", run.horizon_integrators,
                      "the horizon study's fixed-step methods, comma-separated registry names (default: " +
                          join_names(study.integrators) + ")");
  run_cmd->add_flag("--no-horizon", run.no_horizon, "skip the horizon study of the preset");
  run_cmd->add_option("--out", run.out, "the report to write")->required();
  run_cmd->add_option("--stepper", steppers, stepper_help);
  add_isolation_options(run_cmd);
  add_tableau_option(run_cmd);

  std::vector<std::string> merge_inputs;
  std::string merge_out;
  CLI::App* merge = app.add_subcommand("merge", "join shard reports into one");
  merge->add_option("reports", merge_inputs, "shard reports")->required();
  merge->add_option("--out", merge_out, "the merged report")->required();

  ScoreArgs score;
  CLI::App* score_cmd = app.add_subcommand(
      "score", "accuracy and drift of another program's trajectory CSV against the suite's reference");
  score_cmd->add_option("scene", score.scene, "a shipped scene's name or a scene JSON file");
  score_cmd->add_option("trajectory", score.csv, "the trajectory CSV (the columns `rollbench trajectory` writes)");
  score_cmd->add_option("--peers", score.peers,
                        "a peer file (docs/formats.md, \"Peer runs\"): another program's solves, written as report "
                        "runs to --out");
  score_cmd->add_option("--into", score.into, "with --peers: the `rollbench run` report to add the runs to");
  score_cmd->add_option("--t-end", score.t_end, "end time, as the run's (default: the scene's t_end)");
  score_cmd->add_option("--dt-out", score.dt_out,
                        "spacing of the output times, as the run's --dt-out (default: the runner's 0.25)");
  score_cmd->add_option("--cache", score.cache, "directory for cached reference solutions");
  score_cmd->add_option("--out", score.out, "write the JSON here instead of standard output");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "rollbench: %s\n", e.what());
    return 2;
  }

  try {
    rb::register_plugin_steppers(steppers, rb::plugin_isolation(stepper_isolation, stepper_timeout));
    const std::vector<std::string> tableau_methods = rb::add_tableau_files(
        tableau_files, [](const std::string& note) { std::fprintf(stderr, "rollbench: note: %s\n", note.c_str()); });
    if (app.got_subcommand("list")) return run_list(list_markdown);
    if (app.got_subcommand("trajectory")) return run_trajectory(traj);
    if (app.got_subcommand("landscape")) return run_landscape(land);
    if (app.got_subcommand("reversibility")) return run_reversibility(rev);
    if (app.got_subcommand("run")) return run_sweep_command(run, tableau_methods);
    if (app.got_subcommand("merge")) return run_merge(merge_inputs, merge_out);
    if (app.got_subcommand("score")) return run_score(score);
  } catch (const rb::InputError& e) {
    std::fprintf(stderr, "rollbench: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rollbench: internal error: %s\n", e.what());
    return 1;
  }
  return 2;
}

// ns per step of every registered fixed-step integrator on three scenes,
// through the suite's interface (what the sweep times). Counters:
// ns_per_step and rhs_per_step. Run with --benchmark_out=FILE.json for the
// analysis; --benchmark_min_time=0.01 is the quick mode CI uses.
#include <benchmark/benchmark.h>

#include "integrators/registry.hpp"
#include "problems/scene.hpp"

namespace {

constexpr long kSteps = 1000;
constexpr double kH = 1e-3;

void bench_steps(benchmark::State& state, const rb::Problem* problem, const rb::Integrator* method) {
  rb::RunOptions options;
  options.h = kH;
  options.t_end = kSteps * kH;
  rb::Cost cost;
  for (auto _ : state) {
    const rb::RunResult run = method->integrate(*problem, options);
    benchmark::DoNotOptimize(run.final_state.data());
    cost = run.cost;
  }
  const double steps = static_cast<double>(cost.steps) * static_cast<double>(state.iterations());
  state.counters["ns_per_step"] =
      benchmark::Counter(steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["rhs_per_step"] = static_cast<double>(cost.rhs_evals) / static_cast<double>(cost.steps);
}

}  // namespace

int main(int argc, char** argv) {
  static std::vector<rb::Problem> problems;
  for (const char* name : {"valley-sideways", "bowl-3d", "gaussian-hills"})
    problems.push_back(rb::make_problem(rb::load_scene(name)));
  for (const rb::Problem& p : problems)
    for (const auto& m : rb::registry()) {
      if (m->adaptive()) continue;
      benchmark::RegisterBenchmark(("steps/" + p.name() + "/" + m->name()).c_str(), bench_steps, &p, m.get())
          ->Unit(benchmark::kMicrosecond);
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

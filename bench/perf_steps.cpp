// ns per step of every registered fixed-step integrator on three scenes,
// through the suite's interface (what the sweep times). Counters:
// ns_per_step and rhs_per_step. Run with --benchmark_out=FILE.json for the
// analysis; --benchmark_min_time=0.01 is the quick mode CI uses.
#include <benchmark/benchmark.h>

#include <chrono>

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
  double steps = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    const rb::RunResult run = method->integrate(*problem, options);
    benchmark::DoNotOptimize(run.final_state.data());
    cost = run.cost;
    steps += static_cast<double>(run.cost.steps);
  }
  // measured here rather than as an inverted rate, so the unit reads ns
  const double elapsed_ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  state.counters["ns_per_step"] = elapsed_ns / steps;
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

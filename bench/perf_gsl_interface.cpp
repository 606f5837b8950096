// The suite's interface overhead on a library stepper (docs/design.md, "Fair
// comparisons"): ns per step of GSL's rk4 on valley-sideways's flat_rhs
//   interface: rb::find_integrator("gsl-rk4").integrate (allocation of the
//              GSL objects, the rhs callback with its finiteness check and
//              counters, the shared fixed-step loop with check_step after
//              every step and check_full at t_end);
//   direct:    gsl_odeiv2_step_alloc and a gsl_odeiv2_step_apply loop on the
//              same rhs, nothing else;
//   paired:    both alternately in one loop, timed by the thread's CPU clock,
//              so that frequency changes and other processes on a busy
//              machine hit both alike; counter interface_over_direct.
// Counters: ns_per_step. Run with --benchmark_out=FILE.json for the analysis.
#include <benchmark/benchmark.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "bench/side_by_side.hpp"
#include "integrators/families/gsl/gsl.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"

namespace {

constexpr long kSteps = 1000;
constexpr double kH = 1e-3;

const rb::Problem& valley() {
  static const rb::Problem problem = rb::make_problem(rb::load_scene("valley-sideways"));
  return problem;
}

void set_ns_per_step(benchmark::State& state) {
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(kSteps) * 1e-9 * state.iterations(),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// One run through the suite's interface; returns the final x.
double run_interface(const rb::Integrator& method, const rb::RunOptions& options) {
  const rb::RunResult run = method.integrate(valley(), options);
  if (run.status != rb::Status::ok || run.cost.steps != kSteps) std::abort();
  return run.final_state[rb::kOffsetAlpha];
}

int direct_rhs(double /*t*/, const double y[], double dydt[], void* params) {
  static_cast<const rb::Problem*>(params)->flat_rhs(y, dydt);
  return GSL_SUCCESS;
}

// One run with GSL called directly; returns the final x.
double run_direct() {
  gsl_odeiv2_system sys{&direct_rhs, nullptr, rb::kFlatSize, const_cast<rb::Problem*>(&valley())};
  gsl_odeiv2_step* step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk4, rb::kFlatSize);
  rb::FlatState y = valley().y0(), yerr;
  for (long i = 0; i < kSteps; ++i) {
    const double t = static_cast<double>(i) * kH;
    if (gsl_odeiv2_step_apply(step, t, kH, y.data(), yerr.data(), nullptr, nullptr, &sys) != GSL_SUCCESS) std::abort();
  }
  gsl_odeiv2_step_free(step);
  return y[rb::kOffsetAlpha];
}

rb::RunOptions options() {
  rb::RunOptions o;
  o.h = kH;
  o.t_end = kSteps * kH;
  return o;
}

void BM_gsl_rk4_interface(benchmark::State& state) {
  const rb::Integrator& method = rb::find_integrator("gsl-rk4");
  const rb::RunOptions o = options();
  for (auto _ : state) benchmark::DoNotOptimize(run_interface(method, o));
  set_ns_per_step(state);
}

void BM_gsl_rk4_direct(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(run_direct());
  set_ns_per_step(state);
}

void BM_gsl_rk4_paired(benchmark::State& state) {
  const rb::Integrator& method = rb::find_integrator("gsl-rk4");
  const rb::RunOptions o = options();
  const std::vector<double> ns = rb::bench::cpu_ns_in_rotation(state, 2, [&](int i) {
    if (i == 0) {
      benchmark::DoNotOptimize(run_interface(method, o));
    } else {
      benchmark::DoNotOptimize(run_direct());
    }
  });
  const double steps = static_cast<double>(kSteps) * static_cast<double>(state.iterations());
  state.counters["interface_ns_per_step"] = ns[0] / steps;
  state.counters["direct_ns_per_step"] = ns[1] / steps;
  state.counters["interface_over_direct"] = ns[0] / ns[1];
}

}  // namespace

BENCHMARK(BM_gsl_rk4_interface)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_gsl_rk4_direct)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_gsl_rk4_paired)->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  rb::gsl_errors_off();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

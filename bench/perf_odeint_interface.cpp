// The interface's own cost (docs/design.md, "Fair comparisons"): ns per step of
// Boost.Odeint's runge_kutta4 on the same right-hand side (Problem::flat_rhs
// on valley-sideways),
//   interface: rb::find_integrator("odeint-rk4").integrate, i.e.
//              drive_fixed_step with its per-step check_step and copies;
//   direct:    a do_step loop on the same OdeintSystem (its stages' margins
//              noted, as in every run), no per-step checks;
//   direct_n:  odeint's integrate_n_steps on it;
//   direct_checked: the direct loop plus Problem::check_step after each step,
//              to tell the check's share from the rest of the interface.
// interface_vs_direct times both alternately in one benchmark and reports
// overhead = interface / direct - 1 (the issue asks for at most 5 %).
// Counter ns_per_step everywhere. Run with --benchmark_out=FILE.json.
#include <benchmark/benchmark.h>

#include <boost/numeric/odeint/integrate/integrate_n_steps.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <functional>

#include "bench/side_by_side.hpp"
#include "integrators/families/odeint/odeint.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"

namespace {

namespace ode = boost::numeric::odeint;
using rb::OdeintState;
using rb::OdeintSystem;

constexpr long kSteps = 1000;
constexpr double kH = 1e-3;

const rb::Problem& valley() {
  static const rb::Problem problem = rb::make_problem(rb::load_scene("valley-sideways"));
  return problem;
}

OdeintState start() {
  OdeintState x;
  std::copy_n(valley().y0().data(), rb::kFlatSize, x.begin());
  return x;
}

void per_step(benchmark::State& state, long steps_per_iteration) {
  state.counters["ns_per_step"] =
      benchmark::Counter(static_cast<double>(steps_per_iteration) * static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// one run through the suite's interface
rb::RunResult run_interface() {
  rb::RunOptions options;
  options.h = kH;
  options.t_end = kSteps * kH;
  return rb::find_integrator("odeint-rk4").integrate(valley(), options);
}

// the same steps called directly
OdeintState run_direct(rb::Cost& evals) {
  ode::runge_kutta4<OdeintState> stepper;
  const OdeintSystem sys{&valley(), &evals};
  OdeintState x = start();
  double t = 0.0;
  for (long i = 0; i < kSteps; ++i, t += kH) stepper.do_step(sys, x, t, kH);
  return x;
}

void interface(benchmark::State& state) {
  for (auto _ : state) {
    const rb::RunResult run = run_interface();
    benchmark::DoNotOptimize(run.final_state.data());
  }
  per_step(state, kSteps);
}

void direct(benchmark::State& state) {
  for (auto _ : state) {
    rb::Cost evals;
    OdeintState x = run_direct(evals);
    benchmark::DoNotOptimize(x.data());
  }
  per_step(state, kSteps);
}

void direct_n(benchmark::State& state) {
  for (auto _ : state) {
    rb::Cost evals;
    OdeintState x = start();
    ode::runge_kutta4<OdeintState> stepper;
    ode::integrate_n_steps(std::ref(stepper), OdeintSystem{&valley(), &evals}, x, 0.0, kH, kSteps);
    benchmark::DoNotOptimize(x.data());
  }
  per_step(state, kSteps);
}

void direct_checked(benchmark::State& state) {
  for (auto _ : state) {
    rb::Cost evals;
    ode::runge_kutta4<OdeintState> stepper;
    const OdeintSystem sys{&valley(), &evals};
    OdeintState x = start();
    rb::FlatState y;
    bool ok = true;
    double t = 0.0;
    for (long i = 0; i < kSteps && ok; ++i, t += kH) {
      stepper.do_step(sys, x, t, kH);
      std::copy_n(x.begin(), rb::kFlatSize, y.data());
      ok = valley().check_step(y).status == rb::Status::ok;
    }
    benchmark::DoNotOptimize(x.data());
    benchmark::DoNotOptimize(ok);
  }
  per_step(state, kSteps);
}

// both, alternating, so that clock and cache drift hit them alike
// (bench/side_by_side.hpp), in thread CPU time
void interface_vs_direct(benchmark::State& state) {
  const std::vector<double> ns = rb::bench::cpu_ns_in_rotation(state, 2, [](int i) {
    if (i == 0) {
      const rb::RunResult run = run_interface();
      benchmark::DoNotOptimize(run.final_state.data());
    } else {
      rb::Cost evals;
      OdeintState x = run_direct(evals);
      benchmark::DoNotOptimize(x.data());
    }
  });
  const double steps = static_cast<double>(kSteps) * static_cast<double>(state.iterations());
  state.counters["interface_ns_per_step"] = ns[0] / steps;
  state.counters["direct_ns_per_step"] = ns[1] / steps;
  state.counters["overhead"] = ns[0] / ns[1] - 1.0;
}

}  // namespace

BENCHMARK(interface)->Unit(benchmark::kMicrosecond);
BENCHMARK(direct)->Unit(benchmark::kMicrosecond);
BENCHMARK(direct_n)->Unit(benchmark::kMicrosecond);
BENCHMARK(direct_checked)->Unit(benchmark::kMicrosecond);
BENCHMARK(interface_vs_direct)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();

// What projecting R onto SO(3) costs next to what it is paid on: one flat
// right-hand side of a scene, the Newton-Schulz polar step rk4-projected
// uses, and the SVD of rk4-projected-svd, side by side in one benchmark
// (bench/side_by_side.hpp). Each projection gets a fresh R off SO(3) by
// about 1e-9 (an RK4 step's drift at h ~ 1e-2). Each variant runs in
// batches of kBatch calls, so that reading the thread clock (a system call)
// is not what is measured. Counters: ns per call of each and their ratios to
// one rhs.
#include <benchmark/benchmark.h>

#include "bench/side_by_side.hpp"
#include "problems/scene.hpp"
#include "problems/so3.hpp"

namespace {

constexpr int kBatch = 1000;

void BM_projection_vs_rhs(benchmark::State& state) {
  const rb::Problem problem = rb::make_problem(rb::load_scene("valley-sideways"));
  const rb::FlatState y = problem.y0();
  rb::FlatState dy;
  // a rotation with an off-SO(3) perturbation of 1e-9, varied per call so
  // that nothing is hoisted out of the loop
  const rb::Mat3 R = rb::so3_exp(rb::Vec3(0.3, -0.2, 0.5));
  rb::Mat3 drift;
  drift << 1, 2, -1, 0.5, -1, 2, 1, 1, -0.5;
  drift *= 1e-9;
  const std::vector<double> ns = rb::bench::cpu_ns_in_rotation(state, 3, [&](int i) {
    for (int k = 0; k < kBatch; ++k) {
      const rb::Mat3 M = R + (1.0 + 1e-3 * static_cast<double>(k % 7)) * drift;
      if (i == 0) {
        problem.flat_rhs(y.data(), dy.data());
        benchmark::DoNotOptimize(dy.data());
      } else if (i == 1) {
        rb::Mat3 P = rb::project_to_so3_newton_schulz(M);
        benchmark::DoNotOptimize(P.data());
      } else {
        rb::Mat3 P = rb::project_to_so3(M);
        benchmark::DoNotOptimize(P.data());
      }
    }
  });
  const double n = static_cast<double>(state.iterations()) * kBatch;
  state.counters["rhs_ns"] = ns[0] / n;
  state.counters["newton_schulz_ns"] = ns[1] / n;
  state.counters["svd_ns"] = ns[2] / n;
  state.counters["newton_schulz_over_rhs"] = ns[1] / ns[0];
  state.counters["svd_over_rhs"] = ns[2] / ns[0];
}

}  // namespace

BENCHMARK(BM_projection_vs_rhs)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();

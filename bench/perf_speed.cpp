// Are rollbench's own steps as fast as they could be? ns per step on
// valley-sideways and bumpy-long, all in this one binary:
//   rk4, rkmk4:             the suite's methods through rb::Integrator, with
//                           the landscape given as a formula (native code
//                           where a C compiler is at hand, see
//                           problems/formula_native.hpp; the tape otherwise);
//   rk4-hand, rkmk4-hand:   the same methods hand-coded on the same landscape
//                           compiled in (bench/hand_coded_ball.hpp), no
//                           interface;
//   odeint-rk4, gsl-rk4:    the library peers through the same interface.
// side_by_side runs one scene's six in turn in each iteration (rotating the
// order), so that clock drift and frequency changes hit them alike, times
// each run in thread CPU time, and reports the ratios: rk4 / rk4-hand and
// rkmk4 / rkmk4-hand (the issue asks <= 1.3), rk4 / odeint-rk4, rk4 /
// gsl-rk4 and rkmk4 / rk4. The binary repeats each benchmark 9 times unless
// told otherwise and ends with a table of the median ratios.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bench/hand_coded_ball.hpp"
#include "bench/side_by_side.hpp"
#include "integrators/families/gsl/gsl.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"

namespace {

constexpr long kSteps = 1000;
constexpr double kH = 1e-3;

rb::RunOptions run_options() {
  rb::RunOptions o;
  o.h = kH;
  o.t_end = kSteps * kH;
  return o;
}

// The sum of the final state's 14 entries. The whole state, not one entry:
// with the hand-coded peers inlined, the compiler would otherwise drop the
// rotation (which no other entry depends on) and time a third less work.
double checksum(const double* y) {
  double s = 0.0;
  for (int i = 0; i < rb::kFlatSize; ++i) s += y[i];
  return s;
}

using Variant = std::function<double()>;
constexpr const char* kVariantNames[] = {"rk4", "rk4-hand", "rkmk4", "rkmk4-hand", "odeint-rk4", "gsl-rk4"};
constexpr int kCount = 6;

// One scene's six variants and the check that the peers compute its motion.
struct SceneBench {
  std::string scene;
  std::vector<Variant> variants;
  std::function<double()> worst_peer_difference;
};

template <class Surface>
SceneBench make_scene_bench(const std::string& scene, Surface surface) {
  const auto problem = std::make_shared<const rb::Problem>(rb::make_problem(rb::load_scene(scene)));
  const rb::BallParams& p = problem->model().params();
  const rb::hand_coded::Ball<Surface> ball{surface, p.radius, p.mass, p.gravity};
  rb::hand_coded::Flat y0;
  std::copy_n(problem->y0().data(), rb::kFlatSize, y0.begin());
  // the registry looked up once, outside the timed runs
  const auto suite = [problem](const char* name) -> Variant {
    const rb::Integrator* method = &rb::find_integrator(name);
    return [problem, method] {
      const rb::RunResult run = method->integrate(*problem, run_options());
      if (run.status != rb::Status::ok || run.cost.steps != kSteps) std::abort();
      return checksum(run.final_state.data());
    };
  };
  SceneBench b{scene,
               {suite("rk4"), [ball, y0] { return checksum(rb::hand_coded::rk4(ball, y0, kH, kSteps).data()); },
                suite("rkmk4"), [ball, y0] { return checksum(rb::hand_coded::rkmk4(ball, y0, kH, kSteps).data()); },
                suite("odeint-rk4"), suite("gsl-rk4")},
               {}};
  // The hand-coded peers must compute the same motion, or the ratio means
  // nothing: their final states agree with the suite's to rounding.
  b.worst_peer_difference = [problem, ball, y0] {
    const rb::FlatState rk4 = rb::find_integrator("rk4").integrate(*problem, run_options()).final_state;
    const rb::FlatState rkmk4 = rb::find_integrator("rkmk4").integrate(*problem, run_options()).final_state;
    const rb::hand_coded::Flat rk4_hand = rb::hand_coded::rk4(ball, y0, kH, kSteps);
    const rb::hand_coded::Flat rkmk4_hand = rb::hand_coded::rkmk4(ball, y0, kH, kSteps);
    double worst = 0.0;
    for (int i = 0; i < rb::kFlatSize; ++i) {
      worst = std::max(worst, std::abs(rk4[i] - rk4_hand[static_cast<std::size_t>(i)]));
      worst = std::max(worst, std::abs(rkmk4[i] - rkmk4_hand[static_cast<std::size_t>(i)]));
    }
    return worst;
  };
  return b;
}

const std::vector<SceneBench>& scene_benches() {
  static const std::vector<SceneBench> benches = {
      make_scene_bench("valley-sideways", rb::hand_coded::ValleySurface{}),
      make_scene_bench("bumpy-long", rb::hand_coded::BumpySurface{}),
  };
  return benches;
}

using rb::bench::thread_cpu_ns;

void single(benchmark::State& state, const Variant* run) {
  double ns = 0.0;
  for (auto _ : state) {
    const double a = thread_cpu_ns();
    benchmark::DoNotOptimize((*run)());
    ns += thread_cpu_ns() - a;
  }
  state.counters["ns_per_step"] = ns / (static_cast<double>(kSteps) * static_cast<double>(state.iterations()));
}

// the ratios reported, as (counter, numerator, denominator)
struct Ratio {
  const char* counter;
  int num, den;
};
constexpr Ratio kRatios[] = {{"rk4_over_hand", 0, 1},
                             {"rkmk4_over_hand", 2, 3},
                             {"rk4_over_odeint", 0, 4},
                             {"rk4_over_gsl", 0, 5},
                             {"rkmk4_over_rk4", 2, 0}};

void side_by_side(benchmark::State& state, const SceneBench* b) {
  const std::vector<double> ns = rb::bench::cpu_ns_in_rotation(
      state, kCount, [b](int i) { benchmark::DoNotOptimize(b->variants[static_cast<std::size_t>(i)]()); });
  const double steps = static_cast<double>(kSteps) * static_cast<double>(state.iterations());
  for (int i = 0; i < kCount; ++i)
    state.counters[std::string(kVariantNames[i]) + "_ns"] = ns[static_cast<std::size_t>(i)] / steps;
  for (const Ratio& r : kRatios)
    state.counters[r.counter] = ns[static_cast<std::size_t>(r.num)] / ns[static_cast<std::size_t>(r.den)];
}

// The console output plus a closing table of the side-by-side medians.
class TableReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const std::string name = run.benchmark_name();
      const std::size_t at = name.find("side_by_side/");
      if (at == std::string::npos) continue;
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name != "median") continue;
      std::string scene = name.substr(at + 13);
      scene = scene.substr(0, scene.find_first_of("/_"));  // the scene alone, not "_median"
      for (const auto& [counter, value] : run.counters) medians_[scene][counter] = value.value;
    }
  }
  void print_table() const {
    for (const auto& [scene, medians] : medians_) {
      std::printf("\nside by side, %s, h = %g, %ld steps per run (median over repetitions)\n", scene.c_str(), kH,
                  kSteps);
      for (const char* v : kVariantNames) std::printf("  %-12s %8.1f ns/step\n", v, medians.at(std::string(v) + "_ns"));
      for (const Ratio& r : kRatios)
        std::printf("  %-12s / %-12s %6.3f\n", kVariantNames[r.num], kVariantNames[r.den], medians.at(r.counter));
    }
  }

 private:
  std::map<std::string, std::map<std::string, double>> medians_;
};

}  // namespace

int main(int argc, char** argv) {
  rb::gsl_errors_off();
  for (const SceneBench& b : scene_benches()) {
    const double worst = b.worst_peer_difference();
    if (worst > 1e-12) {
      std::fprintf(stderr, "the hand-coded peers differ from the suite by %g on %s\n", worst, b.scene.c_str());
      return 1;
    }
    for (int i = 0; i < kCount; ++i)
      benchmark::RegisterBenchmark(("speed/" + b.scene + "/" + kVariantNames[i]).c_str(), single,
                                   &b.variants[static_cast<std::size_t>(i)])
          ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("speed/side_by_side/" + b.scene).c_str(), side_by_side, &b)
        ->Unit(benchmark::kMillisecond);
  }

  // medians by default: 9 repetitions, aggregates only
  std::vector<char*> args(argv, argv + argc);
  const auto given = [&](const char* flag) {
    return std::any_of(args.begin(), args.end(),
                       [&](const char* a) { return std::strncmp(a, flag, std::strlen(flag)) == 0; });
  };
  static char repetitions[] = "--benchmark_repetitions=9";
  static char aggregates[] = "--benchmark_report_aggregates_only=true";
  if (!given("--benchmark_repetitions")) args.push_back(repetitions);
  if (!given("--benchmark_report_aggregates_only")) args.push_back(aggregates);
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
  TableReporter display;
  benchmark::RunSpecifiedBenchmarks(&display);
  display.print_table();
  benchmark::Shutdown();
  return 0;
}

// Are rollbench's own steps as fast as they could be? ns per step on
// valley-sideways, all in this one binary:
//   rk4, rkmk4:             the suite's methods through rb::Integrator, with
//                           the landscape given as a formula;
//   rk4-hand, rkmk4-hand:   the same methods hand-coded on a compiled valley
//                           (bench/hand_coded_valley.hpp), no interface;
//   odeint-rk4, gsl-rk4:    the library peers through the same interface.
// side_by_side runs all six in turn in each iteration (rotating the order),
// so that clock drift and frequency changes hit them alike, times each run
// in thread CPU time, and reports the ratios: rk4 / rk4-hand and rkmk4 / rkmk4-hand (the issue asks <= 1.3),
// rk4 / odeint-rk4, rk4 / gsl-rk4 and rkmk4 / rk4. The binary repeats each
// benchmark 9 times unless told otherwise and ends with a table of the
// median ratios.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "bench/hand_coded_valley.hpp"
#include "bench/side_by_side.hpp"
#include "integrators/gsl.hpp"
#include "integrators/registry.hpp"
#include "problems/scene.hpp"

namespace {

constexpr long kSteps = 1000;
constexpr double kH = 1e-3;

const rb::Problem& valley() {
  static const rb::Problem problem = rb::make_problem(rb::load_scene("valley-sideways"));
  return problem;
}

rb::hand_coded::Valley hand_valley() {
  const rb::BallParams& p = valley().model().params();
  return {p.radius, p.mass, p.gravity};
}

rb::hand_coded::Flat start() {
  rb::hand_coded::Flat y;
  std::copy_n(valley().y0().data(), rb::kFlatSize, y.begin());
  return y;
}

// One run of kSteps steps; returns the sum of the final state's 14 entries.
// The whole state, not one entry: with the hand-coded peers inlined, the
// compiler would otherwise drop the rotation (which no other entry depends
// on) and time a third less work.
using Variant = double (*)();

double checksum(const double* y) {
  double s = 0.0;
  for (int i = 0; i < rb::kFlatSize; ++i) s += y[i];
  return s;
}

double run_suite(const rb::Integrator& method) {
  static const rb::RunOptions options = [] {
    rb::RunOptions o;
    o.h = kH;
    o.t_end = kSteps * kH;
    return o;
  }();
  const rb::RunResult run = method.integrate(valley(), options);
  if (run.status != rb::Status::ok || run.cost.steps != kSteps) std::abort();
  return checksum(run.final_state.data());
}

// the registry looked up once, outside the timed runs
double rk4() {
  static const rb::Integrator& m = rb::find_integrator("rk4");
  return run_suite(m);
}
double rkmk4() {
  static const rb::Integrator& m = rb::find_integrator("rkmk4");
  return run_suite(m);
}
double odeint_rk4() {
  static const rb::Integrator& m = rb::find_integrator("odeint-rk4");
  return run_suite(m);
}
double gsl_rk4() {
  static const rb::Integrator& m = rb::find_integrator("gsl-rk4");
  return run_suite(m);
}
double rk4_hand() { return checksum(rb::hand_coded::rk4(hand_valley(), start(), kH, kSteps).data()); }
double rkmk4_hand() { return checksum(rb::hand_coded::rkmk4(hand_valley(), start(), kH, kSteps).data()); }

struct Named {
  const char* name;
  Variant run;
};
constexpr Named kVariants[] = {{"rk4", rk4},
                               {"rk4-hand", rk4_hand},
                               {"rkmk4", rkmk4},
                               {"rkmk4-hand", rkmk4_hand},
                               {"odeint-rk4", odeint_rk4},
                               {"gsl-rk4", gsl_rk4}};
constexpr int kCount = sizeof kVariants / sizeof kVariants[0];

using rb::bench::thread_cpu_ns;

void single(benchmark::State& state, Variant run) {
  double ns = 0.0;
  for (auto _ : state) {
    const double a = thread_cpu_ns();
    benchmark::DoNotOptimize(run());
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

void side_by_side(benchmark::State& state) {
  const std::vector<double> ns =
      rb::bench::cpu_ns_in_rotation(state, kCount, [](int i) { benchmark::DoNotOptimize(kVariants[i].run()); });
  const double steps = static_cast<double>(kSteps) * static_cast<double>(state.iterations());
  for (int i = 0; i < kCount; ++i) state.counters[std::string(kVariants[i].name) + "_ns"] = ns[i] / steps;
  for (const Ratio& r : kRatios) state.counters[r.counter] = ns[r.num] / ns[r.den];
}

// The hand-coded peers must compute the same motion, or the ratio means
// nothing: their final states agree with the suite's to rounding.
bool peers_agree() {
  static const rb::RunOptions options = [] {
    rb::RunOptions o;
    o.h = kH;
    o.t_end = kSteps * kH;
    return o;
  }();
  const rb::FlatState rk4 = rb::find_integrator("rk4").integrate(valley(), options).final_state;
  const rb::FlatState rkmk4 = rb::find_integrator("rkmk4").integrate(valley(), options).final_state;
  const rb::hand_coded::Flat rk4_hand = rb::hand_coded::rk4(hand_valley(), start(), kH, kSteps);
  const rb::hand_coded::Flat rkmk4_hand = rb::hand_coded::rkmk4(hand_valley(), start(), kH, kSteps);
  double worst = 0.0;
  for (int i = 0; i < rb::kFlatSize; ++i) {
    worst = std::max(worst, std::abs(rk4[i] - rk4_hand[static_cast<std::size_t>(i)]));
    worst = std::max(worst, std::abs(rkmk4[i] - rkmk4_hand[static_cast<std::size_t>(i)]));
  }
  if (worst > 1e-12) std::fprintf(stderr, "the hand-coded peers differ from the suite by %g\n", worst);
  return worst <= 1e-12;
}

// The console output plus a closing table of the side-by-side medians.
class TableReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.benchmark_name().find("side_by_side") == std::string::npos) continue;
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name != "median") continue;
      for (const auto& [name, counter] : run.counters) medians_[name] = counter.value;
    }
  }
  void print_table() const {
    if (medians_.empty()) return;
    std::printf("\nside by side, valley-sideways, h = %g, %ld steps per run (median over repetitions)\n", kH, kSteps);
    for (const Named& v : kVariants)
      std::printf("  %-12s %8.1f ns/step\n", v.name, medians_.at(std::string(v.name) + "_ns"));
    for (const Ratio& r : kRatios)
      std::printf("  %-12s / %-12s %6.3f\n", kVariants[r.num].name, kVariants[r.den].name, medians_.at(r.counter));
  }

 private:
  std::map<std::string, double> medians_;
};

}  // namespace

int main(int argc, char** argv) {
  rb::gsl_errors_off();
  if (!peers_agree()) return 1;
  for (const Named& v : kVariants)
    benchmark::RegisterBenchmark((std::string("speed/") + v.name).c_str(), single, v.run)
        ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("speed/side_by_side", side_by_side)->Unit(benchmark::kMillisecond);

  // medians by default: 9 repetitions, aggregates only
  std::vector<char*> args(argv, argv + argc);
  const auto given = [&](const char* flag) {
    return std::any_of(args.begin(), args.end(), [&](const char* a) { return std::strncmp(a, flag, std::strlen(flag)) == 0; });
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

#pragma once
// Timing several variants side by side in one Google Benchmark: each
// iteration runs every variant once, the first one rotating, so that clock
// drift, frequency changes and cache order hit them alike.
#include <benchmark/benchmark.h>
#include <time.h>

#include <vector>

namespace rb::bench {

// This thread's CPU time in ns: unlike wall time, it leaves out the time the
// thread waits for a core, which on a shared machine is most of the noise.
inline double thread_cpu_ns() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e9 * static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec);
}

// Calls run_one(i) for i = 0 … count-1 in every iteration, starting from a
// different i each time; returns each variant's total thread CPU ns.
template <class RunOne>
std::vector<double> cpu_ns_in_rotation(benchmark::State& state, int count, RunOne run_one) {
  std::vector<double> ns(static_cast<std::size_t>(count), 0.0);
  long round = 0;
  for (auto _ : state) {
    for (int k = 0; k < count; ++k) {
      const int i = static_cast<int>((round + k) % count);
      const double a = thread_cpu_ns();
      run_one(i);
      ns[static_cast<std::size_t>(i)] += thread_cpu_ns() - a;
    }
    ++round;
  }
  return ns;
}

}  // namespace rb::bench

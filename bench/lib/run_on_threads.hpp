#pragma once
// The runs of a study on --jobs threads: a shared counter hands out the
// indices. The runs that fork (isolated plug-ins) wait until the pool has
// ended and run on the calling thread alone: a child forked while another
// thread holds a lock (the allocator's, a static's guard) can wait on it
// forever. The sweep and the horizon study share it.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

namespace rb {

// The most --jobs a sweep takes (docs/bad-input.md); more is refused.
inline constexpr int kMaxJobs = 1024;

// The threads that run jobs: at least 1, at most one per core (a
// machine that does not say how many it has gets jobs, up to kMaxJobs).
inline int threads_for(int jobs) {
  const unsigned cores = std::thread::hardware_concurrency();
  int threads = std::clamp(jobs, 1, kMaxJobs);
  if (cores > 0 && static_cast<unsigned>(threads) > cores) threads = static_cast<int>(cores);
  return threads;
}

// run(i) for every i < n, on threads_for(jobs) threads where !forks(i) and
// then on this thread where forks(i); while the pool works, this thread
// calls tick(number of runs done) every 50 ms. A thread the system refuses
// (std::system_error) is not an abort: the threads started so far do the
// work, and with none started this thread does it.
template <class Forks, class Run, class Tick>
void run_on_threads(std::size_t n, int jobs, const Forks& forks, const Run& run, const Tick& tick) {
  std::vector<std::size_t> in_pool, forking;
  for (std::size_t i = 0; i < n; ++i) (forks(i) ? forking : in_pool).push_back(i);
  std::atomic<std::size_t> next{0}, done{0};
  const auto work = [&] {
    for (std::size_t k = next++; k < in_pool.size(); k = next++) {
      run(in_pool[k]);
      ++done;
    }
  };
  std::vector<std::thread> pool;
  struct JoinAll {  // whatever leaves this function, no joinable thread is destroyed (std::terminate)
    std::vector<std::thread>& threads;
    ~JoinAll() {
      for (std::thread& t : threads)
        if (t.joinable()) t.join();
    }
  } join_all{pool};
  const int threads = threads_for(jobs);
  pool.reserve(static_cast<std::size_t>(threads));  // a failed emplace_back then only fails to start a thread
  try {
    for (int j = 0; j < threads; ++j) pool.emplace_back(work);
  } catch (const std::system_error&) {
    // too many threads for the system (its limits, its memory): go on with those started
  }
  if (pool.empty()) work();
  while (done < in_pool.size()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    tick(done.load());
  }
  for (std::thread& t : pool) t.join();
  for (const std::size_t i : forking) run(i);
}

}  // namespace rb

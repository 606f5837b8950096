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
#include <thread>
#include <vector>

namespace rb {

// run(i) for every i < n, on max(1, jobs) threads where !forks(i) and then
// on this thread where forks(i); while the pool works, this thread calls
// tick(number of runs done) every 50 ms.
template <class Forks, class Run, class Tick>
void run_on_threads(std::size_t n, int jobs, const Forks& forks, const Run& run, const Tick& tick) {
  std::vector<std::size_t> in_pool, forking;
  for (std::size_t i = 0; i < n; ++i) (forks(i) ? forking : in_pool).push_back(i);
  std::atomic<std::size_t> next{0}, done{0};
  std::vector<std::thread> pool;
  for (int j = 0; j < std::max(1, jobs); ++j)
    pool.emplace_back([&] {
      for (std::size_t k = next++; k < in_pool.size(); k = next++) {
        run(in_pool[k]);
        ++done;
      }
    });
  while (done < in_pool.size()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    tick(done.load());
  }
  for (std::thread& t : pool) t.join();
  for (const std::size_t i : forking) run(i);
}

}  // namespace rb

#include "bench/lib/self_convergence.hpp"

#include <algorithm>
#include <cmath>

namespace rb {

std::vector<SelfDifference> self_differences(const std::vector<const FitRun*>& group) {
  std::vector<SelfDifference> out;
  for (const FitRun* coarse : group) {
    if (!coarse->ok || !(coarse->h > 0.0)) continue;
    for (const FitRun* fine : group) {
      if (!fine->ok || std::abs(fine->h / coarse->h - 0.5) > 1e-9 || fine->stop_time != coarse->stop_time) continue;
      out.push_back({coarse->h, component_distances(coarse->end, fine->end)});
      break;
    }
  }
  std::sort(out.begin(), out.end(), [](const SelfDifference& a, const SelfDifference& b) { return a.h < b.h; });
  return out;
}

}  // namespace rb

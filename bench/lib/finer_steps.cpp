#include "bench/lib/finer_steps.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "bench/lib/fit_run.hpp"
#include "bench/lib/group_orders.hpp"

namespace rb {

std::vector<SweepTask> finer_step_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                        const std::vector<RunRecord>& records, std::size_t next_index) {
  std::map<std::string, std::size_t> scene_of;
  for (std::size_t s = 0; s < scenes.size(); ++s) scene_of[scenes[s].scene.name] = s;
  using Key = std::pair<std::size_t, std::string>;  // (scene, method)
  std::vector<Key> keys;
  std::map<Key, std::vector<FitRun>> groups;
  for (const RunRecord& r : records) {
    if (r.method.adaptive || !scene_of.count(r.scene)) continue;
    const Key key{scene_of.at(r.scene), r.method.name};
    if (!groups.count(key)) keys.push_back(key);
    groups[key].push_back(fit_run(r));
  }
  std::vector<SweepTask> out;
  const long most = std::min(kMaxExtendedSteps, spec.max_steps);
  for (const Key& key : keys) {
    const std::vector<FitRun>& runs = groups.at(key);
    std::vector<const FitRun*> group;
    double smallest = kNaN;
    for (const FitRun& r : runs) {
      group.push_back(&r);
      if (r.h > 0.0 && !(r.h >= smallest)) smallest = r.h;
    }
    const SweepScene& s = scenes[key.first];
    if (!wants_finer_steps(group_orders(group, {s.reference.error, s.omega_scale}))) continue;
    const double t_end = s.problem.t_end();
    const double h = step_taken(smallest / 2.0, t_end);
    if (!(h > 0.0) || std::ceil(t_end / h - 1e-9) > static_cast<double>(most)) continue;
    out.push_back({next_index + out.size(), key.first, key.second, h, kNaN, spec.controller});
  }
  return out;
}

}  // namespace rb

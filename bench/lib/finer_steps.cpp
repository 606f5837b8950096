#include "bench/lib/finer_steps.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "bench/lib/fit_run.hpp"
#include "bench/lib/group_orders.hpp"

namespace rb {

bool finer_step_may_run(Status status) {
  switch (status) {
    case Status::ok:
    case Status::diverged:
    case Status::lift_off:
    case Status::curvature:
    case Status::domain:
    case Status::chart_limit: return true;
    default: return false;
  }
}

bool failed_runs_want_finer_steps(const std::array<ComponentOrder, kErrorComponentCount>& orders,
                                  Status smallest_step) {
  if (!finer_step_may_run(smallest_step)) return false;
  return std::any_of(orders.begin(), orders.end(), [](const ComponentOrder& o) {
    return o.reference.at_floor == 0 && o.judgement.reason == "failed runs";
  });
}

std::vector<SweepTask> finer_step_tasks(const SweepSpec& spec, const std::vector<SweepScene>& scenes,
                                        const std::vector<RunRecord>& records, std::size_t next_index) {
  std::map<std::string, std::size_t> scene_of;
  for (std::size_t s = 0; s < scenes.size(); ++s) scene_of[scenes[s].scene.name] = s;
  using Key = std::pair<std::size_t, std::string>;  // (scene, method)
  std::vector<Key> keys;
  std::map<Key, std::vector<FitRun>> groups;
  std::map<Key, const RunRecord*> smallest_run;  // the run at the smallest step
  for (const RunRecord& r : records) {
    if (r.method.adaptive || !scene_of.count(r.scene)) continue;
    const Key key{scene_of.at(r.scene), r.method.name};
    if (!groups.count(key)) keys.push_back(key);
    groups[key].push_back(fit_run(r));
    if (!smallest_run.count(key) || r.h < smallest_run[key]->h) smallest_run[key] = &r;
  }
  std::vector<SweepTask> out;
  const long most = std::min(kMaxExtendedSteps, spec.max_steps);
  for (const Key& key : keys) {
    const std::vector<FitRun>& runs = groups.at(key);
    std::vector<const FitRun*> group;
    for (const FitRun& r : runs) group.push_back(&r);
    const double smallest = smallest_run.at(key)->h;  // a fixed-step run's h is > 0
    const SweepScene& s = scenes[key.first];
    // without a reference no run has an error, and none fails for that
    if (s.reference.points.empty()) continue;
    const auto orders = group_orders(group, order_scale(s));
    if (!wants_finer_steps(orders) && !failed_runs_want_finer_steps(orders, smallest_run.at(key)->status)) continue;
    const double t_end = s.problem.t_end();
    const double h = step_taken(smallest / 2.0, t_end);
    if (!(h > 0.0) || std::ceil(t_end / h - 1e-9) > static_cast<double>(most)) continue;
    out.push_back({next_index + out.size(), key.first, key.second, h, {}, spec.controller});
  }
  return out;
}

}  // namespace rb

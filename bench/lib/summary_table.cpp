// The console table of a report: per scene and integrator, the observed
// order, the smallest worst error and its time, and the failures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bench/lib/report.hpp"

namespace rb {

std::string summary_table(const Report& report) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-16s %-28s %9s %9s %10s %10s %s\n", "scene", "integrator", "order", "declared",
                "best worst", "its time", "failures");
  out << line;
  std::vector<const FitRun*> seen;  // the first run of each (scene, integrator), in order
  for (const ReportRun& r : report.runs)
    if (std::none_of(seen.begin(), seen.end(),
                     [&](const FitRun* x) { return x->scene == r.fit.scene && x->integrator == r.fit.integrator; }))
      seen.push_back(&r.fit);
  for (const FitRun* first : seen) {
    double best = kNaN, best_time = kNaN;
    int failures = 0;
    for (const ReportRun& x : report.runs) {
      if (x.fit.scene != first->scene || x.fit.integrator != first->integrator) continue;
      if (!x.fit.ok) ++failures;
      const double e = x.fit.error.worst;
      if (std::isfinite(e) && !(e >= best)) best = e, best_time = x.wall_median;
    }
    double observed = kNaN;
    for (const ReportOrder& o : report.orders)
      if (o.scene == first->scene && o.integrator == first->integrator)
        observed = o.components[kHeadlineComponent].reference.slope;
    // an adaptive method (no order fit) shows a dash, not nan
    char order[32] = "—";
    if (std::isfinite(observed)) std::snprintf(order, sizeof order, "%.2f", observed);
    std::snprintf(line, sizeof line, "%-16s %-28s %*s %9d %10.2e %10.2e %d\n", first->scene.c_str(),
                  first->integrator.c_str(), std::isfinite(observed) ? 9 : 11, order, first->declared_order, best,
                  best_time, failures);
    out << line;
  }
  out << "order: the observed order of the contact point (— for adaptive methods or too few steps); best worst: "
         "the smallest worst error (ball radii or rad) over the method's runs; its time: that run's median wall "
         "time (s); failures: runs that did not reach t_end\n";
  return out.str();
}

}  // namespace rb

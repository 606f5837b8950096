"""Cost to accuracy: where a method's work–precision curve first reaches an
error, read by log–log interpolation between the two runs that bracket it."""
import math

from analysis import markdown as md
from analysis import report as rp

# accuracies the cost tables are read at (in the metric's units)
TARGETS = (1e-6, 1e-9)


def rhs_equivalents(r):
    """A run's cost in evaluations of F, an implicit method's Jacobians and Newton passes included (the report's
    `rhs_equivalents`, docs/formats.md#a-run: a Jacobian its columns, a Newton iteration its evaluations, its other
    passes over the model and its linear solve); `rhs_evals` in reports that predate it."""
    value = rp.num(r.entry.get("rhs_equivalents")) if r.entry else math.nan
    return value if math.isfinite(value) else r.rhs_evals


COSTS = (("time", "wall time (s)", rp.wall), ("rhs", "rhs-equivalents", rhs_equivalents))
RHS_EQUIVALENTS = ("Evaluations are counted in rhs-equivalents: an evaluation of F is one, an implicit method's "
                   "Jacobian its columns (14; dla2's 5), each other pass over the model in its Newton iterations "
                   "one, its linear algebra 392 operations to one (docs/formats.md#a-run).")
HOW = ("by log–log interpolation between the two runs that bracket the target along the method's "
       "work–precision curve (successful runs, sorted by cost); \"≤\": the method's cheapest run is already "
       "there, so the cost is an upper bound; \"—\": no run gets there")


def curve(runs, cost_of, metric=rp.DEFAULT_METRIC, floor_value=0.0):
    """(cost, error, run) of the successful runs with both measured, sorted by cost.

    An error below the reference's floor counts as the floor: the run is at
    least that accurate.
    """
    def error(r):
        if floor_value > 0 and rp.below_floor(r, metric):
            return floor_value
        return rp.error(r, metric)
    points = sorted(((cost_of(r), error(r), r) for r in runs if rp.ok(r)), key=lambda p: (p[0], p[1]))
    return [(c, e, r) for c, e, r in points if c > 0 and e > 0 and math.isfinite(c) and math.isfinite(e)]


def crossing(points, target):
    """Where a curve first reaches error <= target: (i, w, bound).

    The place is w of the way (in log error) from points[i] to points[i + 1];
    bound is "≤" (i = 0, w = 0) when the cheapest point is already there.
    None when the curve never gets there.
    """
    if not points:
        return None
    if points[0][1] <= target:
        return 0, 0.0, "≤"
    for i in range(len(points) - 1):
        e0, e1 = points[i][1], points[i + 1][1]
        if e1 <= target < e0:
            return i, (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0)), ""
    return None


def log_between(a, b, w):
    """a^(1-w) b^w; NaN unless both are positive."""
    if w == 0.0:
        return a
    if not (a > 0 and b > 0):
        return math.nan
    return math.exp((1 - w) * math.log(a) + w * math.log(b))


def at_crossing(points, target, value_of):
    """(cost, value_of(run) there, bound) at the crossing; NaNs when never reached."""
    place = crossing(points, target)
    if place is None:
        return math.nan, math.nan, ""
    i, w, bound = place
    j = min(i + 1, len(points) - 1)
    return (log_between(points[i][0], points[j][0], w),
            log_between(value_of(points[i][2]), value_of(points[j][2]), w), bound)


def cost_to_reach(points, target):
    """(cost, bound) at which a curve first reaches error <= target; cost NaN if never."""
    cost, _, bound = at_crossing(points, target, lambda r: 0.0)
    return cost, bound


def reach(runs, targets, metric=rp.DEFAULT_METRIC, floor=0.0, cost_of=rp.wall, value_of=None):
    """{target: (cost, bound)}: where one method's work–precision curve first reaches each target.

    The one cost-to-target of the analysis (the cost tables, the findings'
    and the regime map's cheapest method, the frontier, a pair's ratio per
    timed repeat, the same-tableau table): the method's runs as a curve of
    cost_of (median wall time unless given) against the metric's error,
    read by log–log interpolation (crossing); cost NaN where it never gets
    there. With value_of, {target: (cost, bound, value_of(run) there)},
    interpolated in the same way (at_crossing).
    """
    points = curve(runs, cost_of, metric, floor)
    if value_of is None:
        return {target: cost_to_reach(points, target) for target in targets}
    return {target: (cost, bound, value) for target in targets
            for cost, value, bound in [at_crossing(points, target, value_of)]}


def cost_rows(report, scene, metric=rp.DEFAULT_METRIC):
    """{integrator: {(kind, target): (cost, bound)}} for one scene."""
    floor = rp.floor(report, scene)
    out = {}
    for name, mine in rp.by_integrator(rp.runs(report, scene)).items():
        out[name] = {(kind, target): cost for kind, _, cost_of in COSTS
                     for target, cost in reach(mine, TARGETS, metric, floor, cost_of).items()}
    return out


def cost_section(report, metric=rp.DEFAULT_METRIC):
    lines = [f"## Cost to accuracy ({metric} error)", "",
             f"Cost at which each method's {metric} error ({rp.metric_label(report, metric)}) first reaches the "
             f"target, {HOW}. {RHS_EQUIVALENTS}", ""]
    scenes = [s for s in rp.scenes(report) if rp.runs(report, s)]
    if not scenes:
        return lines + ["No runs.", ""]
    header = ["integrator", "family"]
    for target in TARGETS:
        header += [f"time to {target:.0e} (s)", f"rhs-equivalents to {target:.0e}"]
    cheapest_rows = []
    families = rp.families(report)
    for scene in scenes:
        table = cost_rows(report, scene, metric)
        rows = []
        for name, cells in table.items():
            row = [name, families.get(name) or "—"]
            for target in TARGETS:
                row += [md.fmt(*cells[("time", target)]), md.fmt(*cells[("rhs", target)])]
            rows.append(row)
        lines += [f"### Cost to accuracy — {scene}", ""] + md.table(header, rows) + [""]
        cheapest_rows += cheapest(scene, table)
    lines += [f"## Cheapest method per accuracy ({metric} error)", ""]
    lines += md.table(["scene", f"{metric} error", "cheapest by wall time (s)", "cheapest by rhs-equivalents"],
                      cheapest_rows)
    return lines + [""]


def cheapest(scene, table):
    rows = []
    for target in TARGETS:
        row = [scene, f"{target:.0e}"]
        for kind, _, _ in COSTS:
            # a "≤" cost is an upper bound but still a cost that reaches the target
            reached = [(cells[(kind, target)], name) for name, cells in table.items()
                       if math.isfinite(cells[(kind, target)][0])]
            if reached:
                (cost, bound), name = min(reached)
                row.append(f"{name} ({md.fmt(cost, bound)})")
            else:
                row.append("—")
        rows.append(row)
    return rows

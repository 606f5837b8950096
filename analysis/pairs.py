"""summary.md's "same tableau, flat vs Lie" table: methods that share a
Butcher tableau, one on the flat 14-number view and one on SO(3), read at
the same accuracy, so the difference is the geometry, not the tableau."""
import math

from analysis import costs
from analysis import markdown as md
from analysis import report as rp

# (flat, Lie): same coefficients, same step-size control
PAIRS = (("rk4", "rkmk4"), ("odeint-fehlberg78", "rkmk8"),
         ("odeint-fehlberg78-adaptive", "rkmk-f78-adaptive"), ("odeint-dopri5-adaptive", "rkmk-dp54-adaptive"))
HEADING = "## Same tableau, flat vs Lie"


def reached(runs, metric, floor, target):
    """{"time": (cost, bound), "rhs": (cost, bound), "rotation": value} of one method at one target.

    The rotation error is read where the rhs-evaluation curve crosses the
    target (interpolated like the cost; the cheapest run's own when "≤"); a
    rotation error below the reference's floor counts as the floor.
    """
    def rotation_of(run):
        return floor if floor > 0 and rp.below_floor(run, "rotation") else rp.error(run, "rotation")
    out = {}
    for kind, _, cost_of in costs.COSTS:
        points = costs.curve(runs, cost_of, metric, floor)
        cost, rotation, bound = costs.at_crossing(points, target, rotation_of)
        out[kind] = (cost, bound)
        if kind == "rhs":
            out["rotation"] = rotation
    return out


def pair_rows(report, scene, metric=rp.DEFAULT_METRIC):
    rows = []
    runs = rp.runs(report, scene)
    present = set(rp.integrators(runs))
    families = rp.families(report)
    floor = rp.floor(report, scene)
    for flat, lie in PAIRS:
        if flat not in present or lie not in present:
            continue
        for target in costs.TARGETS:
            for name in (flat, lie):
                mine = [r for r in runs if r["integrator"] == name]
                cell = reached(mine, metric, floor, target)
                rotation = cell["rotation"]
                # at the floor: as accurate as the reference can tell
                at_floor = floor > 0 and math.isfinite(rotation) and rotation <= floor * (1 + 1e-9)
                rows.append([f"{flat} / {lie}", f"{target:.0e}", name, families.get(name) or "—",
                             md.fmt(*cell["time"]), md.fmt(*cell["rhs"]), md.fmt(rotation, "≤" if at_floor else "")])
    return rows


def pairs_section(report, metric=rp.DEFAULT_METRIC):
    lines = [f"{HEADING} ({metric} error)", "",
             f"Each pair shares its Butcher tableau; only the geometry differs. Cost to reach the {metric} "
             f"error, {costs.HOW}. The rotation error is the one the method has there (interpolated in the "
             "same way along the rhs-evaluation curve; with \"≤\", its cheapest run's).", ""]
    any_rows = False
    for scene in rp.scenes(report):
        rows = pair_rows(report, scene, metric)
        if not rows:
            continue
        any_rows = True
        lines += [f"### Same tableau — {scene}", ""]
        lines += md.table(["pair", f"{metric} error", "integrator", "family", "time (s)", "rhs evals",
                           "rotation error there (rad)"], rows) + [""]
    if not any_rows:
        lines += ["No same-tableau pair ran in this report: "
                  + ", ".join(f"{a} / {b}" for a, b in PAIRS) + ".", ""]
    return lines

"""summary.md: observed against declared orders, the cost to reach given
accuracies, the cheapest method at each accuracy, and every failure."""
import math

import numpy as np

from analysis import report as rp

# accuracies the cost tables are read at (contact-point error, in m)
TARGETS = (1e-6, 1e-9)
# the error that work-precision curves and cost tables use: the contact
# point is measured on every scene, exact or computed reference
METRIC = "contact"
COSTS = (("time", "wall time (s)", rp.wall), ("rhs", "rhs evals", lambda r: rp.num(r.get("rhs_evals"))))


def curve(runs, cost_of, metric=METRIC, floor_value=0.0):
    """(cost, error) of the successful runs with both measured, sorted by cost.

    An error below the reference's floor counts as the floor: the run is at
    least that accurate.
    """
    def error(r):
        if floor_value > 0 and rp.below_floor(r, metric):
            return floor_value
        return rp.error(r, metric)
    points = sorted((cost_of(r), error(r)) for r in runs if rp.ok(r))
    return [(c, e) for c, e in points if c > 0 and e > 0 and math.isfinite(c) and math.isfinite(e)]


def cost_to_reach(points, target):
    """The cost at which a work-precision curve first reaches error <= target.

    Log-log interpolation between the last point above the target and the
    first at or below it. Returns (cost, bound): bound is "" for an
    interpolated cost, "≤" when the cheapest point is already below the
    target (no extrapolation), and cost NaN when the curve never gets there.
    """
    if not points:
        return math.nan, ""
    if points[0][1] <= target:
        return points[0][0], "≤"
    for (c0, e0), (c1, e1) in zip(points, points[1:]):
        if e1 <= target < e0:
            w = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(c0) + w * (math.log(c1) - math.log(c0))), ""
    return math.nan, ""


def fmt(value, bound=""):
    if value is None or not math.isfinite(value):
        return "—"
    return f"{bound} {value:.3g}".strip()


def _cell(text):
    # a message may hold '|' or a line break; either would break the table
    return str(text).replace("|", "\\|").replace("\n", " ").strip()


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in rows]
    return lines


def _order_text(value, ci):
    if not math.isfinite(value):
        return "—"
    return f"{value:.2f} ± {ci:.2f}" if math.isfinite(ci) else f"{value:.2f}"


def orders_section(report):
    entries = rp.orders(report)
    if not entries:
        return ["## Observed order", "", "No fixed-step runs: no orders to fit.", ""]
    fitted_here = any(o.get("fitted_here") for o in entries)
    lines = ["## Observed order", ""]
    if fitted_here:
        lines += ["The report has no `orders` section: slopes fitted here over all points above "
                  "10× the reference error (no pre-asymptotic trimming).", ""]
    lines += ["Least-squares slope of log error against log h (contact point and rotation); "
              "pass: no fitted component (contact, centre, omega, rotation) is more than 0.2 below its "
              "declared order. Higher is no failure: for odd-order flat-view methods the leading error "
              "in R is symmetric, so the angle after projection converges one order faster.", ""]
    rows = []
    for o in entries:
        ci = o.get("ci95") or {}
        declared, declared_rot = o.get("declared"), o.get("declared_rotation", o.get("declared"))
        contact, rotation = rp.observed(o, "contact"), rp.observed(o, "rotation")
        passed = o.get("pass")
        if passed is None and o.get("fitted_here"):
            checks = [abs(v - d) <= 0.2 for v, d in ((contact, declared), (rotation, declared_rot))
                      if math.isfinite(v) and d is not None]
            passed = all(checks) if checks else None
        verdict = "—" if passed is None else ("pass" if passed else "**FAIL**")
        fit = o.get("fit") or {}
        h_range = (f"{rp.num(fit.get('h_min')):.3g} – {rp.num(fit.get('h_max')):.3g}"
                   if math.isfinite(rp.num(fit.get("h_min"))) else "—")
        rows.append([o["scene"], o["integrator"], declared if declared is not None else "—",
                     _order_text(contact, rp.num(ci.get("contact"))),
                     declared_rot if declared_rot is not None else "—",
                     _order_text(rotation, rp.num(ci.get("rotation"))), h_range, verdict])
    lines += _table(["scene", "integrator", "declared", "observed (contact)", "declared (R)",
                     "observed (R)", "fit range h (contact)", "verdict"], rows)
    return lines + [""]


def cost_rows(report, scene):
    """{integrator: {(kind, target): (cost, bound)}} for one scene."""
    runs = rp.runs(report, scene)
    out = {}
    for name in rp.integrators(runs):
        mine = [r for r in runs if r["integrator"] == name]
        out[name] = {}
        for kind, _, cost_of in COSTS:
            points = curve(mine, cost_of, floor_value=rp.floor(report, scene))
            for target in TARGETS:
                out[name][(kind, target)] = cost_to_reach(points, target)
    return out


def cost_section(report):
    lines = ["## Cost to accuracy", "",
             f"Cost at which each method's {METRIC}-point error first reaches the target, by log–log "
             "interpolation along its work–precision curve (successful runs only); "
             "\"≤\": its cheapest run is already there; \"—\": never reached.", ""]
    scenes = [s for s in rp.scenes(report) if rp.runs(report, s)]
    if not scenes:
        return lines + ["No runs.", ""]
    header = ["integrator", "family"]
    for target in TARGETS:
        header += [f"time to {target:.0e} (s)", f"rhs evals to {target:.0e}"]
    cheapest_rows = []
    for scene in scenes:
        table = cost_rows(report, scene)
        families = rp.families(report)
        rows = []
        for name, cells in table.items():
            row = [name, families.get(name) or "—"]
            for target in TARGETS:
                row += [fmt(*cells[("time", target)]), fmt(*cells[("rhs", target)])]
            rows.append(row)
        lines += [f"### Cost to accuracy — {scene}", ""] + _table(header, rows) + [""]
        for target in TARGETS:
            row = [scene, f"{target:.0e}"]
            for kind, _, _ in COSTS:
                # a "≤" cost is an upper bound but still a cost that reaches the target
                reached = [(cells[(kind, target)], name) for name, cells in table.items()
                           if math.isfinite(cells[(kind, target)][0])]
                if reached:
                    (cost, bound), name = min(reached)
                    row.append(f"{name} ({fmt(cost, bound)})")
                else:
                    row.append("—")
            cheapest_rows.append(row)
    lines += ["## Cheapest method per accuracy", ""]
    lines += _table(["scene", "error", "cheapest by wall time (s)", "cheapest by rhs evals"], cheapest_rows)
    return lines + [""]


def failures_section(report):
    lines = ["## Failures", ""]
    rows = []
    for r in rp.runs(report):
        if not rp.ok(r):
            rows.append([r["scene"], r["integrator"], rp.setting(r), r["status"],
                         fmt(rp.num(r.get("stop_time"))), r.get("message") or ""])
    for d in rp.drift_runs(report):
        if d.get("status", "ok") != "ok":
            rows.append([d["scene"], d["integrator"] + " (drift run)", f"h={rp.num(d.get('h')):.6g}",
                         d["status"], fmt(rp.num(d.get("stop_time"))), d.get("message") or ""])
    if not rows:
        return lines + ["No run failed.", ""]
    lines += _table(["scene", "integrator", "setting", "status", "stopped at t", "message"], rows)
    return lines + [""]


def header_section(report):
    machine = report.get("machine") or {}
    build = report.get("build") or {}
    lines = ["# rollbench summary", "",
             f"- created: {report.get('created', '—')}, commit {report.get('git', '—')}, "
             f"preset {report.get('preset', '—')}",
             f"- machine: {machine.get('cpu', '—')}, {machine.get('cores', '—')} cores, {machine.get('os', '—')}",
             f"- build: {build.get('compiler', '—')} {build.get('type', '')}"
             + (f" `{build['flags']}`" if build.get("flags") else ""),
             f"- runs: {len(rp.runs(report))}, scenes: {', '.join(rp.scenes(report)) or '—'}", ""]
    refs = rp.section_entries(report, "references")
    if refs:
        rows = [[r["scene"], r.get("kind", "—"), r.get("method", "—"), r.get("cross_check", "—"),
                 fmt(rp.num(r.get("error")))] for r in refs]
        lines += ["## References", ""]
        lines += _table(["scene", "kind", "method", "cross-check", "own error"], rows) + [""]
    return lines


def summary_markdown(report):
    lines = header_section(report) + orders_section(report) + cost_section(report) + failures_section(report)
    return "\n".join(lines).rstrip() + "\n"


def parse_table(markdown, heading):
    """Rows (lists of cells) of the first table after a heading line; for tests and scripts."""
    lines = markdown.splitlines()
    try:
        start = lines.index(heading)
    except ValueError:
        return None
    rows = []
    for line in lines[start + 1:]:
        if line.startswith("|"):
            rows.append([c.strip() for c in line.strip().strip("|").split(" | ")])
        elif rows:
            break
    return rows[2:] if len(rows) >= 2 else []


def as_number(cell):
    """The number in a cost cell ('≤ 1.2e-3' -> 1.2e-3), NaN for '—'."""
    cell = cell.replace("≤", "").strip()
    try:
        return float(cell)
    except ValueError:
        return np.nan

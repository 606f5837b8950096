"""Flat/Lie pairs, in one place for the findings, the regime map and
summary.md's "same tableau, flat vs Lie" table: methods that share a
Butcher tableau, one on the flat 14-number view and one on SO(3), read at
the same accuracy, so the difference is the geometry, not the tableau; and
among them the geometry twins, which differ in nothing else (the suite's own
code, the same controller and error norm)."""
import math

from analysis import costs
from analysis import markdown as md
from analysis import report as rp


def tableau_pairs(runs):
    """(flat, Lie, tableau) of the methods among the runs that share a Butcher tableau.

    From each run's MethodInfo facts (`tableau`, `on_group`, `adaptive`), not
    from a list kept here: a method on the flat view and one on SO(3) with
    the same tableau and the same adaptivity are a pair, so a user's
    `--tableau` file (rk-X, rkmk-X) is paired like the shipped ones. In
    order of first appearance.
    """
    sides = {}
    for r in runs:
        if not r.tableau:
            continue
        side = sides.setdefault((r.tableau, r.adaptive), ([], []))[1 if r.on_group else 0]
        if r.integrator not in side:
            side.append(r.integrator)
    return [(flat, lie, tableau) for (tableau, _), (flats, lies) in sides.items() for flat in flats for lie in lies]


# a library's own code: its own error norm and step-size controller, so its
# method beside a Lie method of the same tableau differs in more than the geometry
LIBRARY_FAMILIES = ("odeint", "gsl", "scipy", "octave")


def geometry_twin(flat_run, lie_run):
    """Whether a flat method of lie's tableau differs from it only in the geometry: the suite's own (no library
    family) with lie's controller (the suite's steppers share the error norm)."""
    return flat_run.family not in LIBRARY_FAMILIES and flat_run.controller == lie_run.controller


def geometry_twins(runs, lie, flats):
    """The flats (of lie's tableau) that differ from lie only in the geometry; where none does, all of them.

    A library's method with the same tableau (odeint's dopri5 beside
    rkmk-dp54-adaptive) has its own norm and controller: it is a variant, a
    library comparison, and stands in only where the runs hold no twin (an
    older report, or a sweep without rk-X-adaptive).
    """
    facts = {r.integrator: r for r in runs}
    twins = [f for f in flats if geometry_twin(facts[f], facts[lie])]
    return twins or list(flats)


def against_twin(runs, lie, flat_ratios):
    """(flat, ratio) of lie against its geometry twin with the smallest measured flat/Lie ratio (the cheapest).

    flat_ratios: {flat of lie's tableau: time_ratio}; the twins are chosen
    among all of them (geometry_twins), then those with a measured ratio
    (finite median) count. None where no twin has one.
    """
    twins = geometry_twins(runs, lie, list(flat_ratios))
    counted = [(ratio[0], flat, ratio) for flat, ratio in flat_ratios.items()
               if flat in twins and math.isfinite(ratio[0])]
    if not counted:
        return None
    _, flat, ratio = min(counted)
    return flat, ratio


def ratio_text(ratio):
    """A time_ratio as text: "≤ 1.23 [1.10–1.40]" (bound, median, [lowest–highest] when repeated); "—" when none."""
    median, low, high, repeats, bound = ratio
    if not math.isfinite(median):
        return "—"
    text = f"{bound} {median:.2f}".strip()
    if repeats > 1:
        text += f" [{low:.2f}–{high:.2f}]"
    return text


HEADING = "## Same tableau, flat vs Lie"


def reached(runs, metric, floor, targets):
    """{target: {"time": (cost, bound), "rhs": (cost, bound), "rotation": value}} of one method.

    The rotation error is read where the rhs-evaluation curve crosses the
    target (interpolated like the cost; the cheapest run's own when "≤"); a
    rotation error below the reference's floor counts as the floor.
    """
    def rotation_of(run):
        return floor if floor > 0 and rp.below_floor(run, "rotation") else rp.error(run, "rotation")
    out = {target: {} for target in targets}
    for kind, _, cost_of in costs.COSTS:
        reached_at = costs.reach(runs, targets, metric, floor, cost_of, rotation_of)
        for target, (cost, bound, rotation) in reached_at.items():
            out[target][kind] = (cost, bound)
            if kind == "rhs":
                out[target]["rotation"] = rotation
    return out


def pair_rows(report, scene, metric=rp.DEFAULT_METRIC):
    rows = []
    runs = rp.runs(report, scene)
    families = rp.families(report)
    floor = rp.floor(report, scene)
    of = rp.by_integrator(runs)
    for flat, lie, _ in tableau_pairs(runs):
        cells = {name: reached(of[name], metric, floor, costs.TARGETS) for name in (flat, lie)}
        for target in costs.TARGETS:
            for name in (flat, lie):
                cell = cells[name][target]
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
             "same way along the rhs-equivalents curve; with \"≤\", its cheapest run's).", ""]
    any_rows = False
    for scene in rp.scenes(report):
        rows = pair_rows(report, scene, metric)
        if not rows:
            continue
        any_rows = True
        lines += [f"### Same tableau — {scene}", ""]
        lines += md.table(["pair", f"{metric} error", "integrator", "family", "time (s)", "rhs-equivalents",
                           "rotation error there (rad)"], rows) + [""]
    if not any_rows:
        lines += ["No same-tableau pair ran in this report (a pair: a flat-view and a Lie-group method with the "
                  "same `tableau` and adaptivity in the runs).", ""]
    return lines


def _sample_cost(k):
    """Cost of a run in timed repeat k (its last repeat where it stopped repeating earlier)."""
    def cost(run):
        samples = rp.samples(run)
        return float(samples[min(k, samples.size - 1)]) if samples.size else rp.wall(run)
    return cost


def time_ratio(runs, flat, lie, metric, floor, target):
    """Flat/Lie wall time to reach target: (median, low, high, repeats, bound) over the timed repeats.

    Repeat k reads both methods' work-precision curves with every run's k-th
    timed sample (costs.HOW), so the spread is that of the timing, measured
    side by side; bound is "≤"/"≥" when a side's cheapest run is already
    there (its cost an upper bound). NaNs when a side never gets there.
    """
    of = rp.by_integrator(runs)
    mine = {n: of.get(n, []) for n in (flat, lie)}
    repeats = max((rp.samples(r).size for n in mine for r in mine[n]), default=0)
    ratios, bound = [], ""
    for k in range(max(1, repeats)):
        cost = _sample_cost(k)
        (a, bound_a), (b, bound_b) = (costs.reach(mine[n], (target,), metric, floor, cost)[target]
                                      for n in (flat, lie))
        if math.isfinite(a) and math.isfinite(b) and b > 0:
            ratios.append(a / b)
            # the flat side's cost an upper bound: so is the ratio; the Lie side's: a lower bound
            bound = {("≤", ""): "≤", ("", "≤"): "≥", ("≤", "≤"): "~"}.get((bound_a, bound_b), "")
    if not ratios:
        return math.nan, math.nan, math.nan, repeats, ""
    ratios.sort()
    n = len(ratios)
    median = ratios[n // 2] if n % 2 else 0.5 * (ratios[n // 2 - 1] + ratios[n // 2])
    return median, ratios[0], ratios[-1], repeats, bound

"""The regime map: where keeping R on SO(3) pays, over the regime study's
grid of generated scenes (inertia ratio × spin × roughness × t_end; the
report's `regime` section, docs/formats.md "Regime").

Per cell and target accuracy: the cheapest method (median wall time to the
target, costs.HOW) and the flat/Lie time ratio of the best same-order pair:
for each declared order with a flat-view and a Lie-group method (MethodInfo
`on_group`) that both reach the target, the cheapest of each side; the cell
shows the order whose cheaper side is the cheapest (the pair that matters at
that accuracy), with the ratio's median and [lowest–highest] over the timed
repeats (pairs.time_ratio). Heat maps regime-<target>.png, a section of
summary.md and a line of its findings.
"""
import math

import matplotlib
import numpy as np

from analysis import costs, figures, pairs
from analysis import markdown as md
from analysis import report as rp

TARGETS = (1e-4, 1e-6, 1e-9)
AXES = ("inertia", "spin", "roughness", "t_end")
HEADING = "## Regime map"
NO_PAIR = "#d0d0d0"  # a heat-map cell where no same-order pair reached the target


def cells(report):
    """The grid's cells as the report lists them ([] for a report of another study)."""
    return (report.get("regime") or {}).get("cells") or []


def axes(report):
    """{axis: [values]} of the grid, in the report's order."""
    given = (report.get("regime") or {}).get("axes") or {}
    return {a: [rp.num(v) for v in given.get(a) or []] for a in AXES}


def figure_name(target):
    return f"regime-{target:.0e}.png"


def _reach(runs, metric, floor, target):
    """{name: (cost, bound)} of the methods whose median-time curve reaches the target."""
    out = {}
    for name in rp.integrators(runs):
        mine = [r for r in runs if r["integrator"] == name]
        cost, bound = costs.cost_to_reach(costs.curve(mine, rp.wall, metric, floor), target)
        if math.isfinite(cost):
            out[name] = (cost, bound)
    return out


def same_order_pairs(runs, reached):
    """[(order, flat, lie)]: per declared order, the cheapest flat and the cheapest Lie method that reach it."""
    facts = {r["integrator"]: (r.get("declared_order"), bool(r.get("on_group"))) for r in runs}
    best = {}
    for name, (cost, _) in reached.items():
        order, on_group = facts[name]
        key = (order, on_group)
        if order is not None and (key not in best or cost < reached[best[key]][0]):
            best[key] = name
    orders = sorted({o for o, _ in best if (o, False) in best and (o, True) in best})
    return [(o, best[(o, False)], best[(o, True)]) for o in orders]


def cell_result(report, scene, target, metric=rp.DEFAULT_METRIC):
    """{"winner": (name, cost, bound) | None, "on_group": bool, "pairs": [(order, flat, lie, ratio)],
    "pair": the headline pair | None} of one scene at one target; ratio as pairs.time_ratio."""
    runs = rp.runs(report, scene)
    floor = rp.floor(report, scene)
    reached = _reach(runs, metric, floor, target)
    result = {"winner": None, "on_group": False, "pairs": [], "pair": None}
    if reached:
        name = min(reached, key=lambda n: (reached[n][0], n))
        result["winner"] = (name, *reached[name])
        result["on_group"] = any(bool(r.get("on_group")) for r in runs if r["integrator"] == name)
    for order, flat, lie in same_order_pairs(runs, reached):
        result["pairs"].append((order, flat, lie, pairs.time_ratio(runs, flat, lie, metric, floor, target)))
    if result["pairs"]:
        result["pair"] = min(result["pairs"], key=lambda p: min(reached[p[1]][0], reached[p[2]][0]))
    return result


def regime_results(report, metric=rp.DEFAULT_METRIC):
    """{(scene, target): cell_result} over every cell and target."""
    return {(c["scene"], t): cell_result(report, c["scene"], t, metric) for c in cells(report) for t in TARGETS}


def _pair_text(pair):
    if pair is None:
        return "—", "—"
    order, flat, lie, ratio = pair
    from analysis.findings import ratio_text  # findings imports this module: late, to avoid a cycle
    return f"order {order}: {flat} / {lie}", ratio_text(ratio)


def _coords(cell):
    return [f"{rp.num(cell.get(a)):g}" for a in AXES]


def regime_section(report, metric=rp.DEFAULT_METRIC, results=None):
    """summary.md's "Regime map": per target, a row per cell ([] without a regime section)."""
    if not cells(report):
        return []
    results = results if results is not None else regime_results(report, metric)
    lines = [HEADING, "",
             f"The regime study's generated scenes (docs/usage.md, \"The regime study\"): per cell and {metric} "
             f"error, the cheapest method by wall time ({costs.HOW}) and the flat / Lie time ratio of the best "
             "same-order pair: per declared order the cheapest flat-view and the cheapest Lie-group method that "
             "reach the target; the order shown is the one whose cheaper side is cheapest. Ratio above 1: the Lie "
             "method is cheaper; median [lowest–highest] over the timed repeats. Figures: "
             + ", ".join(f"`{figure_name(t)}`" for t in TARGETS) + ".", ""]
    for target in TARGETS:
        rows = []
        for cell in cells(report):
            r = results[(cell["scene"], target)]
            winner = r["winner"]
            cheapest = f"{winner[0]} ({md.fmt(winner[1], winner[2])} s)" if winner else "— (no method gets there)"
            rows.append(_coords(cell) + [cheapest, *_pair_text(r["pair"])])
        lines += [f"### Regime map at {metric} error {target:.0e}", ""]
        lines += md.table(["inertia ratio", "spin (rad/s)", "roughness", "t_end (s)", "cheapest",
                           "best same-order pair (flat / Lie)", "flat / Lie time"], rows) + [""]
    return lines


def findings_lines(report, metric=rp.DEFAULT_METRIC, results=None):
    """The findings' line on the regime map ([] without a regime section)."""
    if not cells(report):
        return []
    results = results if results is not None else regime_results(report, metric)
    groups = {True: [], False: []}  # R feeds back (inertia ratio > 1) or the homogeneous ball
    winners = {}
    for cell in cells(report):
        for target in TARGETS:
            r = results[(cell["scene"], target)]
            if r["pair"] is not None and math.isfinite(r["pair"][3][0]):
                groups[rp.num(cell.get("inertia")) > 1].append(r["pair"][3][0])
            if r["winner"]:
                winners[r["winner"][0]] = winners.get(r["winner"][0], 0) + 1
    parts = []
    for where, label in ((True, "where R feeds back (inertia ratio > 1)"), (False, "on the homogeneous ball")):
        values = sorted(groups[where])
        if values:
            parts.append(f"{label} the Lie side of the best same-order pair is cheaper in "
                         f"{sum(1 for v in values if v > 1)} of {len(values)} cell × target, flat/Lie "
                         f"{values[0]:.2f} to {values[-1]:.2f} (median {float(np.median(values)):.2f})")
    total = len(cells(report)) * len(TARGETS)
    top = sorted(winners.items(), key=lambda x: (-x[1], x[0]))[:3]
    cheapest = ", ".join(f"{n} {k}" for n, k in top) if top else "none"
    targets = ", ".join(f"{t:.0e}" for t in TARGETS)
    body = "; ".join(parts) if parts else "no same-order flat/Lie pair reached a target"
    return [f"- Regime map ({len(cells(report))} generated scenes × {metric} error {targets}, figures "
            f"regime-<target>.png): {body}. Cheapest method most often (of {total} cell × target): {cheapest}; "
            f"{total - sum(winners.values())} reached by none."]


# -- heat maps -----------------------------------------------------------------

def _short(name):
    return name.replace("-adaptive", " (a)").replace("odeint-", "")


def heat_map(report, target, metric=rp.DEFAULT_METRIC, results=None):
    """regime-<target>.png: a panel per (t_end, roughness), spin across and inertia ratio up; colour the
    best same-order pair's flat/Lie ratio (log), text the ratio and the cheapest method, a marker where
    the cheapest is a Lie-group method."""
    if not cells(report):
        raise figures.NothingToPlot("the report has no regime section")
    results = results if results is not None else regime_results(report, metric)
    grid = axes(report)
    by_coords = {tuple(rp.num(c.get(a)) for a in AXES): c for c in cells(report)}
    rows, cols = grid["t_end"], grid["roughness"]
    xs, ys = grid["spin"], grid["inertia"]
    ratios = [results[(c["scene"], target)]["pair"][3][0] for c in cells(report)
              if results[(c["scene"], target)]["pair"] is not None]
    finite = [abs(math.log10(v)) for v in ratios if math.isfinite(v) and v > 0]
    span = max([math.log10(2.0)] + finite)
    fig = figures.new_figure(1.0 + 3.4 * len(cols), 0.9 + 2.9 * len(rows))
    axes_grid = fig.subplots(len(rows), len(cols), squeeze=False)
    colours = matplotlib.colormaps["RdBu"].copy()
    colours.set_bad(NO_PAIR)
    image = None
    for i, t_end in enumerate(rows):
        for j, rough in enumerate(cols):
            ax = axes_grid[i][j]
            values = np.full((len(ys), len(xs)), np.nan)
            for yi, inertia in enumerate(ys):
                for xi, spin in enumerate(xs):
                    cell = by_coords.get((inertia, spin, rough, t_end))
                    if cell is None:
                        continue
                    r = results[(cell["scene"], target)]
                    ratio = r["pair"][3] if r["pair"] else None
                    if ratio and math.isfinite(ratio[0]) and ratio[0] > 0:
                        values[yi, xi] = math.log10(ratio[0])
                    text = f"{ratio[4]}{ratio[0]:.2g}" if ratio and math.isfinite(ratio[0]) else "—"
                    text += "\n" + (_short(r["winner"][0]) if r["winner"] else "none")
                    # white on the darkest shades, so that the text stays readable
                    dark = abs(values[yi, xi]) > 0.6 * span
                    ax.text(xi, yi, text, ha="center", va="center", fontsize=6.5,
                            color="white" if dark else "black")
                    if r["winner"] and r["on_group"]:
                        ax.plot(xi + 0.36, yi + 0.32, marker="^", color="white" if dark else "black",
                                markersize=4)
            image = ax.imshow(values, origin="lower", cmap=colours, vmin=-span, vmax=span, aspect="auto")
            ax.set_xticks(range(len(xs)), [f"{v:g}" for v in xs], fontsize=7)
            ax.set_yticks(range(len(ys)), [f"{v:g}" for v in ys], fontsize=7)
            ax.set_title(f"t_end {t_end:g} s, roughness {rough:g}", fontsize=8)
            if i == len(rows) - 1:
                ax.set_xlabel("spin ω·N (rad/s)", fontsize=8)
            if j == 0:
                ax.set_ylabel("inertia ratio", fontsize=8)
    bar = fig.colorbar(image, ax=axes_grid, shrink=0.8)
    ticks = [v for v in (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100)
             if abs(math.log10(v)) <= span + 1e-12]
    bar.set_ticks([math.log10(v) for v in ticks], labels=[f"{v:g}" for v in ticks])
    bar.set_label("flat / Lie time, best same-order pair (above 1: Lie cheaper)", fontsize=8)
    fig.suptitle(f"Regime map at {metric} error {target:.0e}: text = ratio and cheapest method "
                 "(▲: a Lie-group method); grey: no same-order pair reached it", fontsize=9)
    return fig


def heat_maps(report, metric=rp.DEFAULT_METRIC):
    """{file name: Figure} for every target."""
    results = regime_results(report, metric)
    return {figure_name(t): heat_map(report, t, metric, results) for t in TARGETS}

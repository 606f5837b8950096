"""The regime map: where keeping R on SO(3) pays, over the regime study's
grid of generated scenes (inertia ratio × spin × roughness × t_end × bowl ×
speed; the report's `regime` section, docs/formats.md "Regime"), and its
border: the crossover fitted over the cells and checked on the held-out
scenes (analysis/crossover.py).

Per cell and target accuracy: the cheapest method (median wall time to the
target, costs.HOW) and the flat/Lie time ratio of the best twin pair: each
Lie-group method (MethodInfo `on_group`) against its geometry twin, the flat
method of its tableau that differs from it in nothing else (pairs.py, as the
findings pair them: rk-dp54-adaptive with rkmk-dp54-adaptive, not odeint's
dopri5); the cell shows the pair whose cheaper side is the cheapest (the pair
that matters at that accuracy), with the ratio's median and
[lowest–highest] over the timed repeats (pairs.time_ratio); a tie where
that range holds 1. Heat maps
regime-<target>.png, the border's figure regime-border.png, a section of
summary.md and lines of its findings.
"""
import math

import matplotlib
import numpy as np

from analysis import costs, crossover, figures, pairs
from analysis import markdown as md
from analysis import report as rp

TARGETS = (1e-4, 1e-6, 1e-9)
AXES = ("inertia", "spin", "roughness", "t_end", "bowl", "speed")
BORDER_FIGURE = "regime-border.png"
HEADING = "## Regime map"
NO_PAIR = "#d0d0d0"  # a heat-map cell where no twin pair reached the target


def cells(report):
    """The grid's cells as the report lists them ([] for a report of another study)."""
    return (report.get("regime") or {}).get("cells") or []


def held_out(report):
    """The held-out scenes as the report lists them, off-grid cells and shipped scenes ([] when none ran)."""
    return (report.get("regime") or {}).get("held_out") or []


def coord(cell, axis):
    """A cell's coordinate on an axis; None where the report has no such axis (an older grid)."""
    value = cell.get(axis)
    return None if value is None else rp.num(value)


def axes(report):
    """{axis: [values]} of the grid, in the report's order ([None] for an axis an older report lacks)."""
    given = (report.get("regime") or {}).get("axes") or {}
    return {a: [rp.num(v) for v in given[a]] if given.get(a) else [None] for a in AXES}


def figure_name(target):
    return f"regime-{target:.0e}.png"


def _reach(runs, metric, floor, target):
    """{name: (cost, bound)} of the methods whose median-time curve reaches the target."""
    out = {}
    for name, mine in rp.by_integrator(runs).items():
        cost, bound = costs.reach(mine, (target,), metric, floor)[target]
        if math.isfinite(cost):
            out[name] = (cost, bound)
    return out


def twin_pairs(runs, metric, floor, target):
    """[(tableau, flat, lie, ratio)]: each Lie method of a tableau against its geometry twin (pairs.against_twin:
    the same tableau, controller and norm, the cheapest where several), with a measured ratio at the target."""
    by_lie = {}
    for flat, lie, tableau in pairs.tableau_pairs(runs):
        by_lie.setdefault((lie, tableau), []).append(flat)
    out = []
    for (lie, tableau), flats in by_lie.items():
        ratios = {flat: pairs.time_ratio(runs, flat, lie, metric, floor, target) for flat in flats}
        chosen = pairs.against_twin(runs, lie, ratios)
        if chosen is not None:
            out.append((tableau, chosen[0], lie, chosen[1]))
    return out


def cell_result(report, scene, target, metric=rp.DEFAULT_METRIC):
    """{"winner": (name, cost, bound) | None, "on_group": bool, "pairs": [(tableau, flat, lie, ratio)],
    "pair": the headline pair | None} of one scene at one target; ratio as pairs.time_ratio. The headline pair
    is the one whose cheaper side is cheapest (the pair that matters at that accuracy)."""
    runs = rp.runs(report, scene)
    floor = rp.floor(report, scene)
    reached = _reach(runs, metric, floor, target)
    result = {"winner": None, "on_group": False, "pairs": twin_pairs(runs, metric, floor, target), "pair": None}
    if reached:
        name = min(reached, key=lambda n: (reached[n][0], n))
        result["winner"] = (name, *reached[name])
        result["on_group"] = any(r.on_group for r in rp.by_integrator(runs)[name])
    if result["pairs"]:
        def cheaper_side(pair):
            return min(reached[n][0] if n in reached else math.inf for n in pair[1:3])
        result["pair"] = min(result["pairs"], key=cheaper_side)
    return result


def regime_results(report, metric=rp.DEFAULT_METRIC):
    """{(scene, target): cell_result} over every cell and held-out scene and every target, read at the worst
    error over the run as the findings read them, whatever plot.py --errors chose: the map, its border, the
    held-out table and the findings' line state one x* and one count."""
    with rp.errors_read("max"):
        return {(c["scene"], t): cell_result(report, c["scene"], t, metric)
                for c in cells(report) + held_out(report) for t in TARGETS}


def _ratio(result):
    return result["pair"][3] if result["pair"] is not None else (math.nan, math.nan, math.nan, 0, "")


def feeds_back(cell):
    """Whether R feeds back in a grid cell (inertia ratio above 1)."""
    return rp.num(cell.get("inertia")) > 1


def border(report, results):
    """crossover.fit over the cells × targets where R feeds back (decided ones: no tie, no bound)."""
    points = [(c["scene"], crossover.predictor(c), crossover.outcome(_ratio(results[(c["scene"], t)])))
              for c in cells(report) if feeds_back(c) for t in TARGETS]
    return crossover.fit(points)


def held_out_rows(report, results, fit):
    """crossover.check over every held-out scene × target: [(entry, target, X, predicted, measured, hit, ratio)]."""
    keys = [(h, t) for h in held_out(report) for t in TARGETS]
    checked = crossover.check([(h, _ratio(results[(h["scene"], t)])) for h, t in keys], fit)
    return [(h, t, x, predicted, measured, hit, _ratio(results[(h["scene"], t)]))
            for (h, t), (_, x, predicted, measured, hit) in zip(keys, checked)]


def flat_wins(report, results):
    """[(scene, target, ratio)] of the grid cells where the flat side is cheaper beyond the timing's noise."""
    return [(c["scene"], t, _ratio(results[(c["scene"], t)])) for c in cells(report) for t in TARGETS
            if crossover.outcome(_ratio(results[(c["scene"], t)])) == crossover.FLAT]


def _pair_text(pair):
    if pair is None:
        return "—", "—"
    tableau, flat, lie, ratio = pair
    return f"{tableau}: {flat} / {lie}", pairs.ratio_text(ratio)


def _coords(cell):
    return [f"{coord(cell, a):g}" if coord(cell, a) is not None else "—" for a in AXES]


def regime_section(report, metric=rp.DEFAULT_METRIC, results=None):
    """summary.md's "Regime map": per target, a row per cell ([] without a regime section)."""
    if not cells(report):
        return []
    results = results if results is not None else regime_results(report, metric)
    lines = [HEADING, "",
             f"The regime study's generated scenes (docs/usage.md, \"The regime study\"): per cell and {metric} "
             f"error, the cheapest method by wall time ({costs.HOW}) and the flat / Lie time ratio of the best "
             "twin pair: each Lie-group method against its geometry twin, the flat method of its tableau with the "
             "same controller and error norm (the suite's own, not a library's; the cheapest where several); the "
             "pair shown is the one whose cheaper side is cheapest. Ratio above 1: the Lie method is cheaper; "
             "median [lowest–highest] over the timed repeats. Figures: "
             + ", ".join(f"`{figure_name(t)}`" for t in TARGETS) + ".", ""]
    for target in TARGETS:
        rows = []
        for cell in cells(report):
            r = results[(cell["scene"], target)]
            winner = r["winner"]
            cheapest = f"{winner[0]} ({md.fmt(winner[1], winner[2])} s)" if winner else "— (no method gets there)"
            rows.append(_coords(cell) + [cheapest, *_pair_text(r["pair"])])
        lines += [f"### Regime map at {metric} error {target:.0e}", ""]
        lines += md.table(["inertia ratio", "spin (rad/s)", "roughness", "t_end (s)", "bowl a", "speed (m/s)",
                           "|ω0| / Ω", "cheapest", "best twin pair (tableau: flat / Lie)", "flat / Lie time"],
                          [row[:len(AXES)] + [crossover.x_text(crossover.predictor(cell))] + row[len(AXES):]
                           for row, cell in zip(rows, cells(report))]) + [""]
    return lines + held_out_section(report, results)


def _held_out_name(entry):
    return f"{entry['scene']} ({entry.get('kind') or '—'})"


def held_out_section(report, results):
    """The held-out scenes' table: predicted winner against measured ([] when none ran)."""
    if not held_out(report):
        return []
    fit = border(report, results)
    rows = [[_held_out_name(e), f"{target:.0e}", crossover.x_text(x), predicted or "—", measured or "—",
             _pair_text(results[(e["scene"], target)]["pair"])[1],
             {True: "yes", False: "no", None: "—"}[hit]]
            for e, target, x, predicted, measured, hit, _ in held_out_rows(report, results, fit)]
    return ["### Held-out scenes", "",
            "Scenes the crossover was not fitted on: generated off the grid's values and the shipped chaplygin "
            "scenes. Predicted: Lie where |ω0| / Ω is above the fitted x*; measured: the best twin pair's "
            "ratio, a tie where its [lowest–highest] holds 1 (not counted).", ""] + md.table(
        ["scene", "error", "|ω0| / Ω", "predicted", "measured", "flat / Lie time", "right"], rows) + [""]


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
            won = crossover.outcome(_ratio(r))
            if won is not None:  # a measured ratio (a bound is none)
                groups[feeds_back(cell)].append((_ratio(r)[0], won))
            if r["winner"]:
                winners[r["winner"][0]] = winners.get(r["winner"][0], 0) + 1
    parts = []
    for where, label in ((True, "where R feeds back (inertia ratio > 1)"), (False, "on the homogeneous ball")):
        values = sorted(v for v, _ in groups[where])
        if values:
            kinds = (crossover.LIE, crossover.FLAT, crossover.TIE)
            count = {k: sum(1 for _, w in groups[where] if w == k) for k in kinds}
            parts.append(f"{label} the Lie side of the best twin pair is cheaper in {count[crossover.LIE]}, "
                         f"the flat side in {count[crossover.FLAT]}, and {count[crossover.TIE]} are ties (the "
                         f"repeats' range holds 1) of {len(values)} measured cell × target, flat/Lie "
                         f"{values[0]:.2f} to {values[-1]:.2f} (median {float(np.median(values)):.2f})")
    total = len(cells(report)) * len(TARGETS)
    top = sorted(winners.items(), key=lambda x: (-x[1], x[0]))[:3]
    cheapest = ", ".join(f"{n} {k}" for n, k in top) if top else "none"
    targets = ", ".join(f"{t:.0e}" for t in TARGETS)
    body = "; ".join(parts) if parts else "no flat/Lie twin pair reached a target"
    return [f"- Regime map ({len(cells(report))} generated scenes × {metric} error {targets}, figures "
            f"regime-<target>.png): {body}. Cheapest method most often (of {total} cell × target): {cheapest}; "
            f"{total - sum(winners.values())} reached by none."] + border_lines(report, results)


def _x_range(fit):
    if math.isfinite(fit["low"]):
        return f"{fit['x_star']:.2g} [{fit['low']:.2g}–{fit['high']:.2g}]"
    return f"{fit['x_star']:.2g} (no 95 % interval: under 97.5 % of the resampled fits rise)"


def border_lines(report, results):
    """The findings' lines on the border: the crossover, the flat-wins cells and the held-out check."""
    fit = border(report, results)
    if fit is None:
        return ["- Regime border: no crossover to fit: under two decided cells where R feeds back, or one side "
                "wins them all."]
    how = (f"logistic fit of the Lie side winning on log |ω0|/Ω over {fit['points']} decided cell × target "
           f"({fit['cells']} cells) where R feeds back, slope {fit['slope']:.2f} per decade; 95 % interval from "
           f"resampling the cells; figure {BORDER_FIGURE}")
    if not math.isfinite(fit["x_star"]):
        head = f"- Regime border: no crossover: the Lie side does not win more often as |ω0|/Ω grows ({how})."
    else:
        head = (f"- Regime border: the Lie method pays where |ω0|/Ω > {_x_range(fit)}, |ω0| the ball's rotation "
                f"rate and Ω the bowl's frequency at the start ({how}).")
    flat = flat_wins(report, results)
    named = "; ".join(f"{s} at {t:.0e} ({_pair_text(results[(s, t)]['pair'])[1]})" for s, t, _ in flat)
    lines = [head, f"- Flat wins (beyond the timing's noise) in {len(flat)} grid cell × target"
             + (f": {named}." if flat else ".")]
    rows = held_out_rows(report, results, fit)
    if rows:
        decided = [r for r in rows if r[5] is not None]
        hits = sum(1 for r in decided if r[5])
        misses = "; ".join(f"{r[0]['scene']} at {r[1]:.0e} (|ω0|/Ω {crossover.x_text(r[2])}: predicted {r[3]}, "
                           f"measured {r[4]})" for r in decided if not r[5])
        ties = sum(1 for r in rows if r[4] == crossover.TIE)
        unmeasured = len(rows) - len(decided) - ties
        lines.append(f"- Held out ({len({r[0]['scene'] for r in rows})} scenes not fitted on × {len(TARGETS)} "
                     f"targets): the rule predicts the winner in {hits} of {len(decided)} decided"
                     + (f" ({hits / len(decided):.0%})" if decided else "") + f"; {ties} ties and {unmeasured} "
                     "without a measured ratio not counted" + (f". Wrong: {misses}." if misses else "."))
    return lines


# -- heat maps -----------------------------------------------------------------

def _short(name):
    return name.replace("-adaptive", " (a)").replace("odeint-", "")


def heat_map(report, target, metric=rp.DEFAULT_METRIC, results=None):
    """regime-<target>.png: a panel per (t_end, roughness) down and (bowl, speed) across, spin across and
    inertia ratio up in each; colour the best twin pair's flat/Lie ratio (log), text the ratio (= for a
    tie) and the cheapest method, a marker where the cheapest is a Lie-group method."""
    if not cells(report):
        raise figures.NothingToPlot("the report has no regime section")
    results = results if results is not None else regime_results(report, metric)
    grid = axes(report)
    by_coords = {tuple(coord(c, a) for a in AXES): c for c in cells(report)}
    rows = [(t, r) for t in grid["t_end"] for r in grid["roughness"]]
    cols = [(a, v) for a in grid["bowl"] for v in grid["speed"]]
    xs, ys = grid["spin"], grid["inertia"]
    ratios = [_ratio(results[(c["scene"], target)])[0] for c in cells(report)]
    finite = [abs(math.log10(v)) for v in ratios if math.isfinite(v) and v > 0]
    span = max([math.log10(2.0)] + finite)
    fig = figures.new_figure(1.0 + 2.6 * len(cols), 1.2 + 3.0 * len(rows))
    axes_grid = fig.subplots(len(rows), len(cols), squeeze=False)
    fig.subplots_adjust(hspace=0.45, wspace=0.25)  # two-line titles between rows
    colours = matplotlib.colormaps["RdBu"].copy()
    colours.set_bad(NO_PAIR)
    image = None
    for i, (t_end, rough) in enumerate(rows):
        for j, (bowl, speed) in enumerate(cols):
            ax = axes_grid[i][j]
            values = np.full((len(ys), len(xs)), np.nan)
            for yi, inertia in enumerate(ys):
                for xi, spin in enumerate(xs):
                    cell = by_coords.get((inertia, spin, rough, t_end, bowl, speed))
                    if cell is None:
                        continue
                    r = results[(cell["scene"], target)]
                    ratio = r["pair"][3] if r["pair"] else None
                    if ratio and math.isfinite(ratio[0]) and ratio[0] > 0:
                        values[yi, xi] = math.log10(ratio[0])
                    tie = "=" if crossover.outcome(_ratio(r)) == crossover.TIE else ""
                    text = f"{tie}{ratio[4]}{ratio[0]:.2g}" if ratio and math.isfinite(ratio[0]) else "—"
                    text += "\n" + (_short(r["winner"][0]) if r["winner"] else "none")
                    # white on the darkest shades, so that the text stays readable
                    dark = abs(values[yi, xi]) > 0.6 * span
                    ax.text(xi, yi, text, ha="center", va="center", fontsize=5.5,
                            color="white" if dark else "black")
                    if r["winner"] and r["on_group"]:
                        ax.plot(xi + 0.36, yi + 0.32, marker="^", color="white" if dark else "black",
                                markersize=3)
            image = ax.imshow(values, origin="lower", cmap=colours, vmin=-span, vmax=span, aspect="auto")
            ax.set_xticks(range(len(xs)), [f"{v:g}" for v in xs], fontsize=6)
            ax.set_yticks(range(len(ys)), [f"{v:g}" for v in ys], fontsize=6)
            title = f"t_end {t_end:g} s, rough {rough:g}"
            if bowl is not None:
                title += f"\nbowl a {bowl:g}, speed {speed:g} m/s"
            ax.set_title(title, fontsize=7)
            if i == len(rows) - 1:
                ax.set_xlabel("spin ω·N (rad/s)", fontsize=7)
            if j == 0:
                ax.set_ylabel("inertia ratio", fontsize=7)
    bar = fig.colorbar(image, ax=axes_grid, shrink=0.8)
    ticks = [v for v in (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100)
             if abs(math.log10(v)) <= span + 1e-12]
    bar.set_ticks([math.log10(v) for v in ticks], labels=[f"{v:g}" for v in ticks])
    bar.set_label("flat / Lie time, best twin pair (above 1: Lie cheaper)", fontsize=8)
    fig.suptitle(f"Regime map at {metric} error {target:.0e}: text = ratio (=: a tie, the repeats' range holds 1) "
                 "and cheapest method (▲: a Lie-group method); grey: no twin pair reached it", fontsize=9)
    return fig


def border_figure(report, metric=rp.DEFAULT_METRIC, results=None):
    """regime-border.png: flat/Lie time against |ω0|/Ω, grid cells where R feeds back (the fit's points, with
    the repeats' range) by target, the held-out scenes marked, x* with its interval."""
    if not cells(report):
        raise figures.NothingToPlot("the report has no regime section")
    results = results if results is not None else regime_results(report, metric)
    fit = border(report, results)
    fig = figures.new_figure(7.5, 5.0)
    ax = fig.subplots()
    fig.subplots_adjust(bottom=0.13)
    finite_x = [crossover.predictor(c) for c in cells(report) + held_out(report)]
    finite_x = [x for x in finite_x if math.isfinite(x) and x > 0]
    if not finite_x:
        raise figures.NothingToPlot("no cell has a finite |ω0|/Ω")
    x_inf = 2.0 * max(finite_x)  # where a plane's X = ∞ is drawn
    colours = {t: c for t, c in zip(TARGETS, ("tab:blue", "tab:orange", "tab:green"))}
    for target in TARGETS:
        for c in cells(report):
            ratio = _ratio(results[(c["scene"], target)])
            if not feeds_back(c) or crossover.outcome(ratio) is None:
                continue
            x = crossover.predictor(c)
            ax.errorbar([x], [ratio[0]], yerr=[[ratio[0] - ratio[1]], [ratio[2] - ratio[0]]], fmt="o",
                        markersize=3.5, color=colours[target], alpha=0.75, elinewidth=0.8)
        ax.plot([], [], "o", color=colours[target], label=f"grid, error {target:.0e}")
    for e, target, x, _, measured, hit, ratio in held_out_rows(report, results, fit):
        if measured is None:
            continue
        marker = "*" if e.get("kind") == "shipped" else "D"
        ax.plot([x if math.isfinite(x) else x_inf], [ratio[0]], marker, markersize=9 if marker == "*" else 6,
                markerfacecolor="none" if hit is False else colours[target], markeredgecolor="black")
    ax.plot([], [], "*", markersize=9, color="grey", markeredgecolor="black", label="held out: shipped chaplygin-*")
    ax.plot([], [], "D", markersize=6, color="grey", markeredgecolor="black", label="held out: off-grid")
    ax.plot([], [], "D", markersize=6, markerfacecolor="none", markeredgecolor="black",
            label="held out, predicted wrong")
    ax.axhline(1.0, color="black", linewidth=0.8)
    if fit is not None:
        if math.isfinite(fit["x_star"]):
            ax.axvline(fit["x_star"], color="crimson", linewidth=1, label=f"x* = {fit['x_star']:.2g}")
        if math.isfinite(fit["low"]):
            ax.axvspan(fit["low"], fit["high"], color="crimson", alpha=0.12, label="x*'s 95 % interval")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("|ω0| / Ω: the ball's rotation rate over the bowl's frequency (∞: drawn at the right)")
    ax.set_ylabel("flat / Lie time, best twin pair")
    ax.set_title(f"Regime border at {metric} error: above 1 the Lie method is cheaper", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    return fig


def heat_maps(report, metric=rp.DEFAULT_METRIC):
    """{file name: Figure} for every target."""
    results = regime_results(report, metric)
    figs = {figure_name(t): heat_map(report, t, metric, results) for t in TARGETS}
    figs[BORDER_FIGURE] = border_figure(report, metric, results)
    return figs

"""Accuracy against cost and against tolerance, per scene: the full
work–precision figure, the best method of each family (Pareto), and
tolerance proportionality. Every figure names its accuracy metric."""
import math

import numpy as np

from analysis import costs
from analysis import report as rp
from analysis.figures import NothingToPlot, empty_log_axes, legend_right, new_figure, positive, shade_floor


def _cost_axes_label(kind):
    return "wall time per run, median (s)" if kind == "time" else "rhs-equivalents (Jacobians, Newton passes included)"


def _draw_method(ax, runs, name, cost_of, metric, floor, palette, label=None):
    points = costs.curve(runs, cost_of, metric, floor)
    style = palette.style(name)
    adaptive = runs[0].adaptive
    suffix = " (adaptive)" if adaptive and "adaptive" not in name else ""
    ax.plot([c for c, _, _ in points], [e for _, e, _ in points], label=(label or name) + suffix,
            markersize=4.5, linewidth=1.3, markerfacecolor="none" if adaptive else style["color"], **style)


def _finish_axes(ax, scene, metric, kind, floor, title):
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(_cost_axes_label(kind))
    ax.grid(True, which="major", alpha=0.3)
    what = "wall time" if kind == "time" else "rhs-equivalents"
    ax.set_title(f"{scene}: {title}{metric} error against {what}", fontsize=10)
    if not empty_log_axes(ax, "no successful run with a measured error"):
        shade_floor(ax, floor, side="left")
        # the accuracies summary.md reads the costs at
        for target in costs.TARGETS:
            ax.axhline(target, color="#999999", linewidth=0.7, linestyle=":", zorder=0.5)


def _figure(names):
    fig = new_figure(12, max(5.2, 1.2 + 0.16 * (len(names) if len(names) <= 16 else len(names) / 2)))
    return fig, fig.subplots(1, 2, sharey=True)


def _scene_runs(report, scene):
    """(runs, reference floor) of a scene; NothingToPlot without runs."""
    runs = rp.runs(report, scene)
    if not runs:
        raise NothingToPlot(f"no runs for scene {scene}")
    return runs, rp.floor(report, scene)


def work_precision(report, scene, palette, metric=rp.DEFAULT_METRIC):
    """Error against wall time (left) and rhs evaluations (right), every method of the scene."""
    runs, floor = _scene_runs(report, scene)
    of = rp.by_integrator(runs)
    fig, axes = _figure(list(of))
    for ax, (kind, _, cost_of) in zip(axes, costs.COSTS):
        for name in of:
            _draw_method(ax, of[name], name, cost_of, metric, floor, palette)
        _finish_axes(ax, scene, metric, kind, floor, "")
    axes[0].set_ylabel(rp.metric_label(report, metric))
    targets = ", ".join(f"{t:g}" for t in costs.TARGETS)
    legend_right(axes[1], title=f"hollow markers: adaptive\ndotted: {targets} (summary.md)")
    return fig


def pareto_front(points):
    """Indices of the points (cost, error, ...) that no other point beats in both cost and error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


BEST_HOW = ("the member with the lowest mean log10 cost to reach the targets 10^(-k/4) across the family's "
            "accuracy range (from the loosest error every member's cheapest run has to the family's smallest "
            "error); a target a member never reaches counts as ten times the family's largest cost")


def best_of_family(runs, names, cost_of, metric, floor):
    """The member of a family with the lowest cost over the family's accuracy range (BEST_HOW; ties: first name)."""
    of = rp.by_integrator(runs)
    curves = {n: costs.curve(of.get(n, []), cost_of, metric, floor) for n in names}
    curves = {n: c for n, c in curves.items() if c}
    if not curves:
        return None
    loosest = min(max(e for _, e, _ in c) for c in curves.values())
    tightest = min(e for c in curves.values() for _, e, _ in c)
    penalty = math.log10(max(p[0] for c in curves.values() for p in c)) + 1.0
    k_hi, k_lo = math.floor(-4 * math.log10(loosest)), math.ceil(-4 * math.log10(tightest))
    targets = [10.0 ** (-k / 4) for k in range(min(k_hi, k_lo), max(k_hi, k_lo) + 1)] or [loosest]

    def score(name):
        total = 0.0
        for cost, _ in costs.reach(of[name], targets, metric, floor, cost_of).values():
            total += math.log10(cost) if math.isfinite(cost) and cost > 0 else penalty
        return total / len(targets)
    return min(curves, key=lambda n: (score(n), names.index(n)))


def work_precision_best(report, scene, palette, metric=rp.DEFAULT_METRIC):
    """Like work_precision, but one line per family: its best (Pareto) method, chosen per cost axis."""
    runs, floor = _scene_runs(report, scene)
    families = rp.families(report)
    members = {}
    for name in rp.integrators(runs):
        members.setdefault(families.get(name) or "?", []).append(name)
    fig, axes = _figure(list(members))
    for ax, (kind, _, cost_of) in zip(axes, costs.COSTS):
        for family, names in members.items():
            best = best_of_family(runs, names, cost_of, metric, floor)
            if best is None:
                ax.plot([], [], label=f"{family}: no successful run")
                continue
            _draw_method(ax, rp.by_integrator(runs)[best], best, cost_of, metric, floor, palette,
                         label=f"{family}: {best}")
        _finish_axes(ax, scene, metric, kind, floor, "best of each family, ")
    axes[0].set_ylabel(rp.metric_label(report, metric))
    legend_right(axes[1], title="family: its method with the lowest\ncost over the family's accuracy range")
    return fig


def _fitted_line(tol, intercept, slope):
    """The report's fit log10 error = intercept + slope log10 tol, at 20 tolerances over those drawn."""
    xs = np.geomspace(tol.min(), tol.max(), 20)
    return xs, np.power(10.0, intercept + slope * np.log10(xs))


def tolerance(report, scene, palette, metric=rp.DEFAULT_METRIC):
    """Worst error against tolerance per adaptive method, with the report's fit (slope in the legend)."""
    runs = rp.runs(report, scene, adaptive=True)
    if not runs:
        raise NothingToPlot(f"no adaptive runs for scene {scene}")
    fits = {f["integrator"]: f for f in rp.tolerance_fits(report, scene)}
    fig = new_figure(9, 5.5)
    ax = fig.subplots()
    every_tol = []
    for name, theirs in rp.by_integrator(runs).items():
        mine = [r for r in theirs if rp.ok(r)]
        tol, err = positive([rp.tolerance(r) for r in mine], [rp.error(r, metric) for r in mine])
        every_tol += list(tol)
        fit = fits.get(name)
        slope = rp.num((fit or {}).get("slope"))
        # the report fits the worst error; its slope labels the method whatever is drawn
        label = f"{name}: fitted slope {slope:.2f}" if math.isfinite(slope) else f"{name}: no fit"
        style = palette.style(name)
        ax.plot(tol, err, linestyle="none", marker=style["marker"], color=style["color"], markersize=5,
                label=label)
        intercept = rp.num((fit or {}).get("intercept"))
        if tol.size and math.isfinite(slope) and math.isfinite(intercept) and metric == "worst":
            with np.errstate(over="ignore", under="ignore", invalid="ignore"):  # a report's absurd fit: left out
                xs, ys = positive(*_fitted_line(tol, intercept, slope))
            ax.plot(xs, ys, color=style["color"], linestyle=style["linestyle"], linewidth=1.1, label="_fit")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("tolerance (rtol = atol)")
    ax.set_ylabel(rp.metric_label(report, metric))
    ax.grid(True, which="major", alpha=0.3)
    ax.set_title(f"{scene}: tolerance proportionality, {metric} error against tolerance", fontsize=10)
    if not empty_log_axes(ax, "no successful adaptive run"):
        # error = tolerance: where a tolerance would mean exactly what it says
        xs = np.array([min(every_tol), max(every_tol)])
        ax.plot(xs, xs, color="#555555", linewidth=0.9, linestyle=(0, (4, 3)), label="error = tolerance (slope 1)")
    legend_right(ax, title="lines: the report's least-squares fit\n(log10 worst error on log10 tol)")
    return fig

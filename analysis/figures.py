"""Per-scene figures: convergence and drift (work–precision: figures_precision.py).

Each function takes a loaded report, a scene and a style.Palette and returns
a matplotlib Figure (built without pyplot, so no global state piles up), or
raises NothingToPlot saying why there is nothing to draw. Every integrator
of the scene gets exactly one labelled line per axes (an empty one if it
has no data there) so that legends and tests can rely on the count.
"""
import math

import matplotlib

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import numpy as np  # noqa: E402

from analysis import report as rp  # noqa: E402

FLOOR_COLOUR = "#bbbbbb"
BLOW_UP = 1e4  # drift above this is a blow-up; the axes stop there
# values beyond this are not drawn: a log axes' margins around 1e300 leave the double's range (a report may hold
# any finite number, analysis/report_schema.py)
PLOT_MAX = 1e200
GUIDE = {"color": "#888888", "linewidth": 0.8, "linestyle": (0, (4, 3)), "alpha": 0.6, "zorder": 0.5}


class NothingToPlot(Exception):
    """The report has no data for this figure; the message says what is missing."""


def new_figure(width, height):
    return Figure(figsize=(width, height), dpi=110)


def legend_right(ax, handles=None, labels=None, title=None):
    """A legend outside the axes on the right: with a dozen methods it would hide data inside."""
    handles, labels = (handles, labels) if handles else ax.get_legend_handles_labels()
    ncol = 1 if len(labels) <= 16 else 2
    ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7.5, ncol=ncol,
              title=title, title_fontsize=7.5, frameon=False, borderaxespad=0.0)


def empty_log_axes(ax, message):
    """A log-log axes with no points still needs positive limits to be drawn; it says why it is empty."""
    if any(len(line.get_xdata()) for line in ax.lines):
        return False
    ax.set_xlim(1e-3, 1.0)
    ax.set_ylim(1e-3, 1.0)
    ax.text(0.5, 0.5, message, transform=ax.transAxes, ha="center", va="center", fontsize=9, color="#555555")
    return True


def positive(xs, ys):
    """Pairs with both coordinates positive and at most PLOT_MAX (what a log-log axes can show)."""
    xs, ys = np.asarray(xs, float), np.asarray(ys, float)
    if xs.shape != ys.shape:  # a series the run lacks (an integral it did not record): nothing to draw
        return np.array([]), np.array([])
    keep = (xs > 0) & (ys > 0) & (xs <= PLOT_MAX) & (ys <= PLOT_MAX)  # NaN compares false: left out too
    return xs[keep], ys[keep]


def shade_floor(ax, floor, side="right"):
    """Grey band below the reference's own error: nothing there is measured.

    The label goes on the side where the most accurate points are not.
    """
    if not floor or not 0 < floor <= PLOT_MAX:
        return
    lo, hi = ax.get_ylim()
    lo = min(lo, floor / 10)
    ax.axhspan(lo, floor, color=FLOOR_COLOUR, alpha=0.35, zorder=0, linewidth=0)
    x = 0.99 if side == "right" else 0.01
    # inside the band, so that guide labels resting on the floor do not cover it
    ax.text(x, math.sqrt(lo * floor), " below the reference's own error ", transform=ax.get_yaxis_transform(),
            ha=side, va="center", fontsize=7, color="#555555")
    ax.set_ylim(lo, max(hi, floor * 10))


def cap_top(ax, values, what):
    """Keeps a blow-up (1e100) from squashing every other line; says what left the top."""
    values = np.asarray(values, float)
    values = values[np.isfinite(values) & (values > 0)]
    if values.size and values.max() > BLOW_UP:
        lo, _ = ax.get_ylim()
        ax.set_ylim(lo, BLOW_UP)
        ax.text(0.5, 0.98, f"{what} above {BLOW_UP:g} leave the top", transform=ax.transAxes, ha="center",
                va="top", fontsize=7, color="#555555", bbox={"facecolor": "white", "alpha": 0.7, "linewidth": 0})


def power_of_two_ticks(ax, values):
    """Step sizes that are all powers of two get ticks 2^-k at exactly those values."""
    values = sorted({v for v in values if math.isfinite(v) and v > 0})
    if not values:
        return
    k = np.log2(values)
    if np.all(np.abs(k - np.round(k)) < 1e-9):
        ax.set_xticks(values, [f"$2^{{{int(round(e))}}}$" for e in k])
        ax.set_xticks([], minor=True)


def slope_guides(ax, x_anchor, y_anchor, slopes, var="h", at="right", floor=0.0):
    """Faint lines y ∝ x^p through one anchor point, labelled with their slope; the limits stay put.

    Nothing is drawn below floor (the reference's error band).
    """
    xlo, xhi = ax.get_xlim()
    ylo, yhi = ax.get_ylim()
    bottom = max(ylo, floor or 0.0)
    xs = np.geomspace(xlo, xhi, 200)
    for p in sorted(set(slopes)):
        ys = y_anchor * (xs / x_anchor) ** p
        ax.plot(xs, np.where(ys >= bottom, ys, np.nan), label="_guide", **GUIDE)
        # label where the line leaves the visible box, on the side away from the anchor
        inside = (ys >= bottom) & (ys <= yhi)
        if not inside.any():
            continue
        i = np.flatnonzero(inside)[0 if at == "left" else -1]
        text = f"∝ {var}$^{{{p:g}}}$" if p != 1 else f"∝ {var}"
        ax.text(xs[i], ys[i], text, fontsize=8, color="#555555", ha="left" if at == "left" else "right",
                va="bottom")
    ax.set_xlim(xlo, xhi)
    ax.set_ylim(ylo, yhi)


def order_label(order, component):
    """'p = 4.01 ± 0.02, as declared': the report's fit with its 95 % interval and verdict, never a bare slope.

    ci95 is a half-width or [low, high] (docs/formats.md); without an
    interval the order is not shown, since a slope alone cannot be judged.
    """
    value = rp.observed(order, component)
    if not math.isfinite(value):
        return "exact: every step on the plateau" if rp.verdict(order, component) == "exact" else "p: no fit"
    ci = ((order.get("ci95") or {}).get(component))
    if isinstance(ci, list) and len(ci) == 2 and all(math.isfinite(rp.num(c)) for c in ci):
        interval = f"p = {value:.2f} [{rp.num(ci[0]):.2f}, {rp.num(ci[1]):.2f}]"
    elif math.isfinite(rp.num(ci)):
        interval = f"p = {value:.2f} ± {rp.num(ci):.2f}"
    else:
        return f"p: no interval, {rp.verdict(order, component)}"
    return f"{interval}, {rp.verdict(order, component)}"


def convergence(report, scene, palette):
    """Error against step size, log-log: a panel per error component, in the report's order (its error_components)."""
    fixed = rp.runs(report, scene, adaptive=False)
    if not fixed:
        raise NothingToPlot(f"no fixed-step runs for scene {scene}")
    floor = rp.floor(report, scene)
    orders = {o["integrator"]: o for o in rp.orders(report) if o["scene"] == scene}
    panels = rp.components(report)
    fig = new_figure(10, 4.25 * len(panels))
    axes = np.atleast_1d(fig.subplots(len(panels), 1, sharex=True))
    for ax, component in zip(axes, panels):
        anchor = {}  # declared order: the top (largest h) point of each method declaring it
        for name, mine in rp.by_integrator(fixed).items():
            mine = sorted(mine, key=lambda r: r.h)
            good = [r for r in mine if rp.ok(r)]
            h, e = positive([r.h for r in good], [rp.error(r, component) for r in good])
            style = palette.style(name)
            failed = len(mine) - len(good)
            label = f"{name}  {order_label(orders.get(name), component)}" + (f"  [{failed} failed]" if failed else "")
            ax.plot(h, e, label=label, markersize=4.5, linewidth=1.3, **style)
            # below the floor: drawn on the floor, hollow, so the reader sees the run was there
            low = [r.h for r in good if rp.below_floor(r, component)]
            if low and floor > 0:
                ax.plot(low, [floor] * len(low), linestyle="none", marker=style["marker"], color=style["color"],
                        markerfacecolor="none", markersize=5, label="_below floor")
            first = mine[0]
            key = "declared_rotation_order" if component == "rotation" else "declared_order"
            p = first.entry.get(key, first.declared_order)
            if h.size and isinstance(p, (int, float)) and p > 0:
                anchor.setdefault(p, []).append((h[-1], e[-1]))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel(rp.metric_label(report, component))
        ax.grid(True, which="major", alpha=0.3)
        ax.set_title(f"{scene}: {component} error against step size", fontsize=10)
        if empty_log_axes(ax, f"no successful run with a measured {component} error"):
            pass
        elif anchor:
            ax.margins(x=0.05)
            shade_floor(ax, floor, side="right")
            # one guide per declared order, a little below the methods that declare it,
            # so that a method's line can be compared with its own guide
            for p, points in sorted(anchor.items()):
                h_top = max(h for h, _ in points)
                e_top = np.exp(np.mean([np.log(e) for h, e in points if h == h_top]))
                slope_guides(ax, h_top, float(e_top) / 4, [p], at="left", floor=floor)
        legend_right(ax, title="fitted order p ± 95 % interval, the runner's verdict\n(as declared / lower / exact / "
                               "inconclusive; the report's orders)")
    axes[-1].set_xlabel("step size h (s)")
    power_of_two_ticks(axes[-1], [r.h for r in fixed])
    return fig


def _drift_series(ax, entries, key, palette):
    for d in entries:
        t, y = positive(d.get("t") or [], d.get(key) or [])
        style = palette.style(d["integrator"])
        status = d.get("status", "ok")
        label = d["integrator"] + (f" [{status} at t={rp.num(d.get('stop_time')):.3g}]" if status != "ok" else "")
        ax.plot(t, y, label=label, markersize=3, linewidth=1.3, markevery=max(1, t.size // 10), **style)
        if status != "ok" and t.size:
            ax.plot(t[-1], y[-1], marker="x", color="black", markersize=8, label="_stop")
    ax.set_xscale("log")
    ax.set_yscale("log")
    if not empty_log_axes(ax, "no positive values recorded"):
        xs = np.concatenate([line.get_xdata() for line in ax.lines if len(line.get_xdata())])
        ys = np.concatenate([line.get_ydata() for line in ax.lines if len(line.get_ydata())])
        ax.set_ylim(ys.min() / 3, ys.max() * 3)
        cap_top(ax, ys, "values")
        ys = ys[ys <= BLOW_UP]
        # t^1 and t^2 through the middle of the data: linear and quadratic growth at a glance
        slope_guides(ax, float(np.exp(np.mean(np.log(xs)))), float(np.exp(np.median(np.log(ys)))), (1, 2),
                     var="t", at="right")


def energy_key(entry, on_group, flat):
    """The key of the energy error at the nearest rotation, H(polar(R), v, α), where the entry has it, else the
    flat one's (reports that predate it): the flat H hides R's drift off SO(3)
    (docs/model.md#how-the-energy-error-is-measured)."""
    return on_group if on_group in entry else flat


def run_cost(r):
    """A sweep run's cost in rhs-equivalents (`rhs_evals` in older reports): the analysis's cost axis."""
    value = rp.num(r.entry.get("rhs_equivalents"))
    return value if math.isfinite(value) else r.rhs_evals


def drift(report, scene, palette):
    """Energy error (at the nearest rotation where recorded) and rotation defect against time (drift runs) and
    against cost in rhs-equivalents (sweep runs)."""
    series = [dict(d, energy_error=d[energy_key(d, "energy_error_on_group", "energy_error")])
              for d in rp.drift_runs(report, scene) if d.get("t")]
    runs = [r for r in rp.runs(report, scene) if r.entry.get("drift")]
    if not series and not runs:
        raise NothingToPlot(f"no drift runs and no runs with drift for scene {scene}")
    rows = (1 if series else 0) + (1 if runs else 0)
    fig = new_figure(12, 4.6 * rows)
    axes = np.atleast_2d(fig.subplots(rows, 2))
    row = 0
    if series:
        h = sorted({rp.num(d.get("h")) for d in series})
        for ax, key, label, short in (
                (axes[row, 0], "energy_error", "energy error |H(polar R) − H$_0$| (J)", "energy error"),
                (axes[row, 1], "rotation_defect", "rotation defect ‖R$^T$R − I‖$_F$", "rotation defect")):
            _drift_series(ax, series, key, palette)
            ax.set_xlabel("time t (s)")
            ax.set_ylabel(label)
            ax.grid(True, which="major", alpha=0.3)
            ax.set_title(f"{scene}: {short} over a long run (h = {', '.join(f'{x:g}' for x in h)} s)",
                         fontsize=10)
        legend_right(axes[row, 1], title="growth: flat = bounded,\nslope 1 = linear, 2 = quadratic")
        row += 1
    if runs:
        of = rp.by_integrator(runs)
        for ax, key, label in ((axes[row, 0], "energy", "largest energy error max|H(polar R) − H$_0$| (J)"),
                               (axes[row, 1], "rotation_defect", "largest rotation defect ‖R$^T$R − I‖$_F$")):
            def value(r, key=key):
                d = r.entry["drift"]
                return rp.num(d.get(energy_key(d, "energy_on_group", "energy") if key == "energy" else key))
            for name, theirs in of.items():
                mine = sorted((r for r in theirs if rp.ok(r)), key=run_cost)
                x, y = positive([run_cost(r) for r in mine], [value(r) for r in mine])
                style = palette.style(name)
                adaptive = theirs[0].adaptive
                ax.plot(x, y, label=name, markersize=4, linewidth=1.2,
                        markerfacecolor="none" if adaptive else style["color"], **style)
                # failed runs keep their drift up to the stop: crosses, off the lines
                failed = [r for r in theirs if not rp.ok(r)]
                fx, fy = positive([run_cost(r) for r in failed], [value(r) for r in failed])
                if fx.size:
                    ax.plot(fx, fy, linestyle="none", marker="x", color=style["color"], markersize=7,
                            label="_failed")
            ax.set_xscale("log")
            ax.set_yscale("log")
            if not empty_log_axes(ax, "no run with a positive value"):
                cap_top(ax, [y for line in ax.lines for y in line.get_ydata()], "runs")
            ax.set_xlabel("rhs-equivalents (Jacobians, Newton passes included)")
            ax.set_ylabel(label)
            ax.grid(True, which="major", alpha=0.3)
            ax.set_title(f"{scene}: {'energy error' if key == 'energy' else 'rotation defect'} "
                         "of each sweep run against cost", fontsize=10)
        legend_right(axes[row, 1], title="hollow markers: adaptive\n×: a failed run, up to its stop")
    fig.subplots_adjust(hspace=0.32)
    return fig

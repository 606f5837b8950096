"""Figures over all scenes: stability, the scenes themselves, ns per step."""
import csv
import io
import json
import math
import os

import numpy as np

from analysis import landscape, safe_files, stability as stab
from analysis import report as rp
from analysis import style as st
from analysis.figures import NothingToPlot, new_figure

SCENE_MARKERS = ["o", "s", "^", "D", "v", "P", "X", "*", "<", ">"]
STATUS_ORDER = list(st.STATUS_COLOURS)
GRID = 220  # landscape points per axis


def _colour_ticklabels(ax, names, palette):
    for label, name in zip(ax.get_yticklabels(), names):
        label.set_color(st.shade(palette.colour(name), -0.2))


def _finish_step_axes(ax, names, palette, none_x, none_label, xlabel):
    """The stability panels' common axes: methods down, log steps across, "none" left of every step."""
    ax.plot([], [], marker="x", color="black", linestyle="none", label=none_label)
    ax.axvline(none_x * 1.5, color="#999999", linewidth=0.7, linestyle=":")
    ax.set_xscale("log")
    ax.set_yticks(range(len(names)), names, fontsize=8)
    _colour_ticklabels(ax, names, palette)
    ax.set_ylim(len(names) - 0.5, -0.5)
    ax.set_xlabel(xlabel)
    ax.grid(True, axis="x", which="major", alpha=0.3)


def _largest_stable_panel(ax, entries, palette):
    names = rp.integrators(entries)
    scenes = rp.unique(e["scene"] for e in entries)
    known = [rp.stable_h(e) for e in entries if math.isfinite(rp.stable_h(e))]
    tried = [t for e in entries for t in rp.tested_h(e)]
    smallest = min([h for h in known + tried if math.isfinite(h) and h > 0] or [1e-3])
    none_x = smallest / 4  # where "no stable step found" is drawn, left of every real step
    offsets = np.linspace(-0.25, 0.25, len(scenes)) if len(scenes) > 1 else [0.0]
    for j, scene in enumerate(scenes):
        marker = SCENE_MARKERS[j % len(SCENE_MARKERS)]
        for e in (e for e in entries if e["scene"] == scene):
            y = names.index(e["integrator"]) + offsets[j]
            h = rp.stable_h(e)
            colour = palette.colour(e["integrator"])
            if math.isfinite(h):
                ax.plot([h], [y], marker=marker, color=colour, markersize=7, linestyle="none")
                ax.plot([none_x * 1.5, h], [y, y], color=colour, linewidth=0.8, alpha=0.4)
            else:
                ax.plot([none_x], [y], marker="x", color=colour, markersize=7, linestyle="none")
        ax.plot([], [], marker=marker, color="black", linestyle="none", label=scene)
    _finish_step_axes(ax, names, palette, none_x, "no tested step passes",
                      "largest stable step h (s): it and every smaller tested step pass")
    bounds = entries[0].get("thresholds") or {}
    horizon = rp.num(entries[0].get("horizon"))
    parts = [f"to t = {horizon:g} s" if math.isfinite(horizon) else "",
             f"energy error ≤ {rp.num(bounds.get('energy')):g} of the scale" if "energy" in bounds else "",
             f"‖RᵀR − I‖ ≤ {rp.num(bounds.get('rotation_defect')):g}" if "rotation_defect" in bounds else "",
             "no exponential growth" if "growth_exponent" in bounds else ""]
    detail = ", ".join(p for p in parts if p)
    ax.set_title("largest stable step per method and scene" + (f"\n(no stop, {detail})" if detail else "")
                 + "\nrotation defect there: summary.md", fontsize=10)
    ax.text(none_x, -0.6, "none", ha="center", va="bottom", fontsize=7, color="#666666")


# one fill per horizon of the drift-limited step, shortest first (more horizons: the last fill again)
HORIZON_FILLS = ["full", "left", "none"]
BLOW_UP_COLOUR = "#b2182b"


def _limits_panel(ax, entries, palette):
    """Per method and scene: the drift-limited step h*(T) at each horizon (one fill each) and the blow-up step (a
    bar; one per horizon where it moves), joined by a line (analysis/stability.py)."""
    names = rp.integrators(entries)
    scenes = rp.unique(e["scene"] for e in entries)
    times = stab.horizons(entries)
    steps = []
    for e in entries:
        blow, drift = stab.limits(e) or ([], [])
        steps += [rp.num(x.get("h")) for x in blow + drift] + rp.tested_h(e)
    steps = [h for h in steps if math.isfinite(h) and h > 0]
    smallest = min(steps or [1e-3])
    none_x = smallest / 4  # where "no step keeps the bounds" is drawn, left of every real step
    offsets = np.linspace(-0.25, 0.25, len(scenes)) if len(scenes) > 1 else [0.0]
    for j, scene in enumerate(scenes):
        marker = SCENE_MARKERS[j % len(SCENE_MARKERS)]
        for e in (e for e in entries if e["scene"] == scene and stab.limits(e) is not None):
            blow, drift = stab.limits(e)
            y = names.index(e["integrator"]) + offsets[j]
            colour = palette.colour(e["integrator"])
            xs = []
            for k, t in enumerate(times):
                d = stab.drift_at(e, t)
                if d is None:
                    continue
                h = rp.num(d.get("h"))
                fill = HORIZON_FILLS[min(k, len(HORIZON_FILLS) - 1)]
                if math.isfinite(h):
                    ax.plot([h], [y], marker=marker, color=colour, fillstyle=fill, markersize=7, linestyle="none")
                    xs.append(h)
                else:
                    ax.plot([none_x], [y], marker="x", color=colour, markersize=7, linestyle="none")
            bars = sorted({rp.num(b.get("h")) for b in blow if math.isfinite(rp.num(b.get("h")))})
            for h in bars:
                ax.plot([h], [y], marker="|", color=BLOW_UP_COLOUR, markersize=10, markeredgewidth=2,
                        linestyle="none")
            ends = xs + bars
            if ends:
                ax.plot([min(ends), max(ends)], [y, y], color=colour, linewidth=0.8, alpha=0.4)
        ax.plot([], [], marker=marker, color="black", linestyle="none", label=scene)
    for k, t in enumerate(times):
        ax.plot([], [], marker="o", color="black", fillstyle=HORIZON_FILLS[min(k, len(HORIZON_FILLS) - 1)],
                linestyle="none", label=f"h*({t:g} s)")
    ax.plot([], [], marker="|", color=BLOW_UP_COLOUR, markeredgewidth=2, linestyle="none", label="blow-up step")
    _finish_step_axes(ax, names, palette, none_x, "no step keeps the bounds", "step h (s)")
    bounds = entries[0].get("thresholds") or {}
    ax.set_title("drift-limited step h*(T) per horizon (fill)\nand blow-up step (bar) per method and scene\n"
                 f"(h*: energy error ≤ {rp.num(bounds.get('energy')):g} of the scale, "
                 f"‖RᵀR − I‖ ≤ {rp.num(bounds.get('rotation_defect')):g} to T)", fontsize=10)
    ax.text(none_x, -0.6, "none", ha="center", va="bottom", fontsize=7, color="#666666")


def _failure_panel(ax, runs, palette):
    of = rp.by_integrator(runs)
    names = list(of)
    statuses = [s for s in STATUS_ORDER if any(r.status == s for r in runs)]
    statuses += rp.unique(r.status for r in runs if r.status not in STATUS_ORDER)
    left = np.zeros(len(names))
    for status in statuses:
        counts = np.array([sum(1 for r in of[n] if r.status == status) for n in names])
        colour = st.STATUS_COLOURS.get(status, "#444444")
        ax.barh(range(len(names)), counts, left=left, color=colour, label=status, edgecolor="white",
                linewidth=0.5)
        widest = max(1, max(len(of[n]) for n in names))
        for i, c in enumerate(counts):
            # a count only where its segment is wide enough to hold it
            if c and status != "ok" and c / widest > 0.04:
                ax.text(left[i] + c / 2, i, str(c), ha="center", va="center", fontsize=7,
                        color="white" if status in ("diverged", "error", "step-underflow", "max-steps", "crashed",
                                                    "timeout") else "black")
        left += counts
    ax.set_yticks(range(len(names)), names, fontsize=8)
    _colour_ticklabels(ax, names, palette)
    ax.set_ylim(len(names) - 0.5, -0.5)
    ax.set_xlabel("runs (all scenes, step sizes and tolerances)")
    failed = sum(1 for r in runs if r.status != "ok")
    ax.set_title(f"status of every sweep run: {failed} of {len(runs)} failed", fontsize=10)
    status_legend = ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False,
                              title="status", title_fontsize=7.5)
    ax.add_artist(status_legend)
    ax.legend(handles=st.family_legend_handles(palette.family(n) for n in names), fontsize=7.5,
              loc="lower left", bbox_to_anchor=(1.02, 0.0), frameon=False, title="name colour: family",
              title_fontsize=7.5)


def stability(report, palette):
    """Blow-up and drift-limited steps per fixed-step method and scene (left; a report of before: the largest stable
    step) and run statuses per method (right)."""
    entries = rp.stable_steps(report)
    runs = rp.runs(report)
    if not entries and not runs:
        raise NothingToPlot("no stability.largest_stable_h and no runs")
    count = max(len(rp.integrators(entries)), len(rp.integrators(runs)))
    height = 1.6 + 0.32 * count
    fig = new_figure(13 if entries and runs else 7, height)
    axes = fig.subplots(1, 2 if entries and runs else 1, squeeze=False)[0]
    # margins in inches, not fractions: the figure's height grows with the number of methods
    fig.subplots_adjust(bottom=0.8 / height, top=1 - 0.6 / height)
    if entries:
        # a report of before the two limits has one largest stable step per entry
        (_limits_panel if stab.has_limits(entries) else _largest_stable_panel)(axes[0], entries, palette)
        # under the panel: inside, it would cover the methods with the largest steps
        handles, labels = axes[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.27 if runs else 0.5, 0.0),
                   ncol=min(5, len(labels)), fontsize=7.5, frameon=False,
                   title="marker: scene; fill: horizon" if stab.has_limits(entries) else "scene", title_fontsize=7.5)
    if runs:
        _failure_panel(axes[-1], runs, palette)
    else:
        axes[0].legend(handles=st.family_legend_handles(palette.family(n) for n in rp.integrators(entries)),
                       fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False,
                       title="colour: family", title_fontsize=7.5)
    fig.subplots_adjust(wspace=0.4)
    return fig


# -- scenes --------------------------------------------------------------------

def read_trajectory(path, columns=("t", "x", "y")):
    """Some columns of a trajectory CSV (docs/formats.md), by header name: {name: array}."""
    # a regular file within the limit (analysis/safe_files.py): InputFileError, a ValueError, otherwise
    reader = csv.reader(io.StringIO(safe_files.read_text(path, "trajectory", safe_files.TRAJECTORY_LIMIT),
                                    newline=""))
    header = [h.strip() for h in next(reader)]
    for key in columns:
        if key not in header:
            raise ValueError(f"{path}: trajectory CSV has no column '{key}'")
    rows = np.array([[float(v) for v in row] for row in reader if row], dtype=float)
    if rows.size == 0:
        raise ValueError(f"{path}: trajectory CSV has no rows")
    return {k: rows[:, header.index(k)] for k in columns}


def _extent(scene, path):
    """[xmin, xmax, ymin, ymax]: the trajectory with a margin, else the domain, else around the start."""
    domain = scene.get("domain")
    start = (scene.get("start") or {}).get("contact") or [0.0, 0.0]
    if path is not None:
        x0, x1, y0, y1 = path["x"].min(), path["x"].max(), path["y"].min(), path["y"].max()
        pad = max(0.3 * max(x1 - x0, y1 - y0), 0.3)
        box = [x0 - pad, x1 + pad, y0 - pad, y1 + pad]
        if domain:
            box = [max(box[0], domain[0]), min(box[1], domain[1]), max(box[2], domain[2]), min(box[3], domain[3])]
        return box
    if domain:
        return list(domain)
    return [start[0] - 1.0, start[0] + 1.0, start[1] - 1.0, start[1] + 1.0]


def _scene_panel(ax, fig, scene, path, values):
    gx, gy, z = values
    x0, x1, y0, y1 = gx.min(), gx.max(), gy.min(), gy.max()
    z = np.ma.masked_invalid(z)
    if z.count() == 0:
        ax.text(0.5, 0.5, "landscape undefined here", transform=ax.transAxes, ha="center")
    elif np.ptp(z.compressed()) == 0:
        ax.set_facecolor("#e8e4d8")  # a plane: no contours to draw
        ax.text(0.02, 0.02, f"flat, z = {z.compressed()[0]:g}", transform=ax.transAxes, fontsize=7)
    else:
        filled = ax.contourf(gx, gy, z, levels=20, cmap="terrain", alpha=0.85)
        ax.contour(gx, gy, z, levels=filled.levels, colors="k", linewidths=0.3, alpha=0.4)
        bar = fig.colorbar(filled, ax=ax, shrink=0.85, pad=0.02)
        bar.set_label("z = f(x, y) (m)", fontsize=7)
        bar.ax.tick_params(labelsize=6)
    start = (scene.get("start") or {}).get("contact")
    if path is not None:
        ax.plot(path["x"], path["y"], color="crimson", linewidth=1.4, label="contact point")
        ax.plot(path["x"][0], path["y"][0], "o", color="white", markeredgecolor="black", markersize=7,
                label="start")
        ax.plot(path["x"][-1], path["y"][-1], "s", color="black", markersize=6, label="end")
    elif start:
        ax.plot(start[0], start[1], "o", color="white", markeredgecolor="black", markersize=7, label="start")
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.tick_params(labelsize=7)
    text = scene["landscape"] if len(scene["landscape"]) <= 40 else scene["landscape"][:39] + "…"
    ax.set_title(f"{scene.get('name', '?')}\nz = {text}", fontsize=8.5)
    if path is not None:
        ax.text(0.02, 0.98, f"end at t = {path['t'][-1]:g} s", transform=ax.transAxes, fontsize=7,
                va="top", bbox={"facecolor": "white", "alpha": 0.7, "linewidth": 0})


def scene_files(report, scene_dir):
    """{scene name: its JSON file}: the files the run was given (`options.scenes`, as typed, read from
    here), each under the `name` it holds; a shipped scene's name is looked up in scene_dir."""
    files = {}
    for given in (report.get("options") or {}).get("scenes") or []:
        if not isinstance(given, str) or not given.endswith(".json") or not os.path.isfile(given):
            continue
        try:
            name = json.loads(safe_files.read_text(given, "scene file", safe_files.SCENE_LIMIT)).get("name")
        except (ValueError, AttributeError, RecursionError):
            continue
        if isinstance(name, str):
            files.setdefault(name, given)
    return files


def scenes(report, scene_dir, trajectory_dir=None, messages=None, rollbench=landscape.DEFAULT_ROLLBENCH):
    """Each scene's landscape as shaded contours, with the contact-point path where a CSV is given.

    The heights come from `rollbench landscape`; scenes whose JSON cannot be
    read, or that rollbench refuses, are left out with a line in messages.
    """
    messages = messages if messages is not None else []
    if not rp.scenes(report):
        raise NothingToPlot("the report names no scenes")
    files = scene_files(report, scene_dir)
    loaded = []
    for name in rp.scenes(report):
        path = files.get(name) or os.path.join(scene_dir, f"{name}.json")
        try:
            scene = json.loads(safe_files.read_text(path, "scene file", safe_files.SCENE_LIMIT))
            if not isinstance(scene, dict) or not isinstance(scene.get("landscape"), str):
                raise ValueError("no key 'landscape'")
        except (ValueError, RecursionError) as e:
            messages.append(f"scenes.png: left out {name} ({path}: {e})")
            continue
        trajectory = None
        csv_path = os.path.join(trajectory_dir, f"{name}.csv") if trajectory_dir else None
        if csv_path and os.path.exists(csv_path):
            try:
                trajectory = read_trajectory(csv_path)
            except (OSError, ValueError, StopIteration) as e:
                messages.append(f"scenes.png: no trajectory for {name} ({e})")
        try:
            values = landscape.grid(path, GRID, GRID, _extent(scene, trajectory), rollbench)
        except landscape.LandscapeError as e:
            messages.append(f"scenes.png: left out {name} ({e})")
            continue
        loaded.append((scene, trajectory, values))
    if not loaded:
        raise NothingToPlot(f"no scene of the report could be read from {scene_dir}")
    cols = min(3, len(loaded))
    rows = math.ceil(len(loaded) / cols)
    fig = new_figure(5.0 * cols, 4.6 * rows)
    axes = np.atleast_1d(fig.subplots(rows, cols, squeeze=False)).ravel()
    for ax, (scene, trajectory, values) in zip(axes, loaded):
        _scene_panel(ax, fig, scene, trajectory, values)
    for ax in axes[len(loaded):]:
        ax.set_visible(False)
    # one legend for all panels, under them, so that no path is covered
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color="crimson", linewidth=1.4, label="contact point (trajectory CSV)"),
               Line2D([], [], marker="o", color="white", markeredgecolor="black", linestyle="none",
                      markersize=7, label="start"),
               Line2D([], [], marker="s", color="black", linestyle="none", markersize=6, label="end")]
    if not any(t is not None for _, t, _ in loaded):
        handles = handles[1:2]
    fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.02), ncol=3, fontsize=8,
               frameon=False)
    fig.subplots_adjust(wspace=0.35, hspace=0.35)
    return fig


# -- Google Benchmark ----------------------------------------------------------

UNIT_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def perf_entries(perf):
    """(group, integrator, value, per_step) from a Google Benchmark JSON.

    Names like steps/<scene>/<integrator> are grouped by scene. With
    repetitions, the median aggregates stand for the runs.
    """
    benchmarks = [b for b in perf.get("benchmarks") or [] if isinstance(b, dict) and not b.get("error_occurred")]
    if any(b.get("run_type") == "aggregate" for b in benchmarks):
        benchmarks = [b for b in benchmarks if b.get("run_type") == "aggregate" and b.get("aggregate_name") == "median"]
    out = []
    for b in benchmarks:
        name = b.get("run_name") or b.get("name", "?")
        parts = name.split("/")
        group, method = (parts[1], "/".join(parts[2:])) if len(parts) >= 3 else ("", name)
        if isinstance(b.get("ns_per_step"), (int, float)):
            out.append((group, method, float(b["ns_per_step"]), True))
        elif isinstance(b.get("real_time"), (int, float)):
            out.append((group, method, float(b["real_time"]) * UNIT_NS.get(b.get("time_unit", "ns"), 1.0), False))
    return out


def ns_per_step(perf, palette):
    """Horizontal bars of ns per step, one panel per scene, colour = family."""
    entries = perf_entries(perf)
    if not entries:
        raise NothingToPlot("the benchmark file has no benchmarks with a time")
    groups = rp.unique(e[0] for e in entries)
    per_step = all(e[3] for e in entries)
    # methods sorted by their mean time, fastest on top, the same order in every panel
    names = rp.unique(e[1] for e in entries)
    mean = {n: np.mean([e[2] for e in entries if e[1] == n]) for n in names}
    names.sort(key=lambda n: mean[n])
    all_values = [e[2] for e in entries if e[2] > 0] or [1.0]
    fig = new_figure(4.2 * len(groups) + 2.5, 1.4 + 0.27 * len(names))
    axes = fig.subplots(1, len(groups), sharey=True, squeeze=False)[0]
    for ax, group in zip(axes, groups):
        values = {e[1]: e[2] for e in entries if e[0] == group}
        ys = [i for i, n in enumerate(names) if n in values]
        xs = [values[names[i]] for i in ys]
        ax.barh(ys, xs, color=[palette.colour(names[i]) for i in ys], height=0.7)
        for y, x in zip(ys, xs):
            ax.text(x, y, f" {x:,.0f}" if x >= 100 else f" {x:.3g}", va="center", fontsize=6.5)
        # bars from zero unless the times span decades (then the short ones would vanish)
        if max(all_values) / min(all_values) > 30:
            ax.set_xscale("log")
            ax.set_xlim(min(all_values) / 1.5, max(all_values) * 3)
        else:
            ax.set_xlim(0, max(all_values) * 1.15)
        ax.grid(True, axis="x", which="major", alpha=0.3)
        ax.set_xlabel("ns per step" if per_step else "real time per benchmark iteration (ns)")
        ax.set_title((group + ": " if group else "") + ("ns per step" if per_step else "time"), fontsize=10)
    axes[0].set_yticks(range(len(names)), names, fontsize=7.5)
    _colour_ticklabels(axes[0], names, palette)
    axes[0].set_ylim(len(names) - 0.5, -0.5)
    fig.legend(handles=st.family_legend_handles(palette.family(n) for n in names), loc="upper left",
               bbox_to_anchor=(0.91, 0.88), fontsize=7.5, frameon=False, title="family", title_fontsize=7.5)
    return fig

"""The horizon study (docs/usage.md#the-horizon-study): horizon-<scene>.png,
the energy error and the rotation defect (their envelope: the largest in
each log-spaced window) against t on log-log axes with the runner's fitted
growth exponent p of err ~ C t^p in the legend; the "Long horizons" section
of summary.md and its line in the findings. A fit whose early and late
halves disagree (the report's `asymptotic`) reads "not yet asymptotic
(early → late)" instead of one p; a series the report marks the same as an
earlier run's (`same_as`) is drawn and stated once, under both names. A
scene that declares first integrals beyond the energy (the runs'
`invariants`: Routh's, the Chaplygin ball's) gets one more panel per
integral, its relative error drawn and fitted the same way, and its own
table and findings."""
import math

import numpy as np

from analysis import figures
from analysis import markdown as md
from analysis import report as rp

HEADING = "## Long horizons"
INVARIANT_HEADING = "### First integrals beyond the energy"
# (key in a run and in its fit, axis label, short name)
SERIES = (("energy_error", "energy error |H − H$_0$| (J), largest per window", "energy error"),
          ("rotation_defect", "rotation defect ‖R$^T$R − I‖$_F$, largest per window", "rotation defect"))
WINDOW_COLOUR = "#eeeeee"


def runs(report, scene=None):
    """The horizon study's runs of a report ([] for a report without the study), of one scene when given: the
    runs at the study's step, whose growth the figures and findings read (not the price runs)."""
    return [r for r in all_runs(report, scene) if coarsening(r) == 1]


def all_runs(report, scene=None):
    """Every horizon run, the price runs at k h (`coarsening` k > 1) too, of one scene when given."""
    return [r for r in rp.section_entries(report, "horizon.runs") if scene is None or r["scene"] == scene]


def coarsening(run):
    """k of a price run of steps / k steps of k h; 1 for the study's own run (and reports older than them)."""
    k = run.get("coarsening")
    return int(k) if isinstance(k, (int, float)) and k >= 1 else 1


def scenes(report):
    return rp.unique(r["scene"] for r in runs(report))


def fit_of(run, key):
    return (run.get("fit") or {}).get(key) or {}


INVARIANT = "invariant:"


def invariant_names(entries):
    """The names of the first integrals the runs record, in their order."""
    return rp.unique(i.get("name") for r in entries for i in (r.get("invariants") or []) if i.get("name"))


def invariant_view(run, name):
    """The run with the integral's error under the key 'invariant:<name>', its fit under fit[key] and its twin
    (the report's same_as.invariants) under same_as[key], so that what draws and states the energy's series does
    the same for it."""
    key = INVARIANT + name
    found = next((i for i in (run.get("invariants") or []) if i.get("name") == name), {})
    view = dict(run)
    view[key] = found.get("error") or []
    view["fit"] = dict(run.get("fit") or {}, **{key: found.get("fit") or {}})
    twin = ((run.get("same_as") or {}).get("invariants") or {}).get(name)
    view["same_as"] = {key: twin}
    return view


def not_asymptotic(fit):
    """A fit above rounding whose early and late halves disagree (the report's `asymptotic` is false)."""
    return (math.isfinite(rp.num(fit.get("p"))) and fit.get("asymptotic") is False
            and not fit.get("at_rounding"))


def exponent_text(fit):
    """'1.02 ± 0.02', '0.45 ± 0.06 (rounding)', 'not yet asymptotic (0.30 → 0.63)', or '—'."""
    p, ci = rp.num(fit.get("p")), rp.num(fit.get("ci95"))
    if not math.isfinite(p):
        return "—"
    if not_asymptotic(fit):
        return f"not yet asymptotic ({halves_text(fit)})"
    text = f"{p:.2f} ± {ci:.2f}" if math.isfinite(ci) else f"{p:.2f}"
    return text + (" (rounding)" if fit.get("at_rounding") else "")


def same_as(run, key):
    """The integrator whose series this run's equals (the report's `same_as`), or None."""
    return (run.get("same_as") or {}).get(key)


def shown_name(entries, run, key):
    """'rk4 = rkmk4 = cf4' for a run whose series others share, else its name."""
    twins = [r["integrator"] for r in entries if same_as(r, key) == run["integrator"]]
    return " = ".join([run["integrator"]] + twins)


def halves_text(fit):
    early, late = rp.num(fit.get("p_early")), rp.num(fit.get("p_late"))
    if not (math.isfinite(early) and math.isfinite(late)):
        return ""
    return f"{early:.2f} → {late:.2f}"


def count_text(value):
    """10000 -> '10,000'; '—' for a missing count."""
    return f"{value:,}" if isinstance(value, int) else "—"


def kind(run):
    return "R feeds back" if run.get("r_feeds_back") else "homogeneous"


def _legend_label(entries, run, key):
    status = run.get("status", "ok")
    if status != "ok":
        return f"{run['integrator']}: {status} at t = {rp.num(run.get('stop_time')):.3g}"
    fit = fit_of(run, key)
    text = exponent_text(fit)
    return f"{shown_name(entries, run, key)}: " + (text if not_asymptotic(fit) else f"p = {text}")


def _panel(ax, entries, key, label, short, palette):
    window = None
    for r in entries:
        if same_as(r, key):
            continue  # drawn once, under the first run's line
        t, y = figures.positive(r.get("t") or [], r.get(key) or [])
        style = palette.style(r["integrator"])
        ax.plot(t, y, label=_legend_label(entries, r, key), markersize=3, linewidth=1.2, markevery=max(1, t.size // 8),
                **style)
        if r.get("status", "ok") != "ok" and t.size:
            ax.plot(t[-1], y[-1], marker="x", color="black", markersize=8, label="_stop")
        fit = fit_of(r, key)
        p, c = rp.num(fit.get("p")), rp.num(fit.get("log10_c"))
        t_from, t_to = rp.num(fit.get("t_from")), rp.num(fit.get("t_to"))
        if math.isfinite(t_from) and math.isfinite(t_to) and t_from > 0:
            window = (t_from, t_to)
        if math.isfinite(p) and math.isfinite(c) and window:
            # the fitted line over its window: thick and faint, under the data
            tt = np.geomspace(t_from, t_to, 20)
            ax.plot(tt, 10.0 ** c * tt ** p, color=style["color"], linewidth=4, alpha=0.3, label="_fit",
                    zorder=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    if not figures.empty_log_axes(ax, "no positive values recorded"):
        lines = [line for line in ax.lines if len(line.get_ydata()) and line.get_label() != "_fit"]
        xs = np.concatenate([line.get_xdata() for line in lines])
        ys = np.concatenate([line.get_ydata() for line in lines])
        ax.set_ylim(ys.min() / 3, ys.max() * 3)
        figures.cap_top(ax, ys, "values")
        figures.slope_guides(ax, float(np.exp(np.mean(np.log(xs)))),
                             float(np.exp(np.median(np.log(ys[ys <= figures.BLOW_UP])))), (1, 2), var="t")
        levels = [rp.num(fit_of(r, key).get("rounding_level")) for r in entries]
        levels = [v for v in levels if math.isfinite(v) and v > 0]
        if levels:
            ax.axhline(max(levels), color="#999999", linewidth=0.8, linestyle=":", label="_rounding")
            ax.text(0.01, max(levels), " rounding level 100 ε √n", transform=ax.get_yaxis_transform(),
                    fontsize=7, color="#555555", va="bottom")
    if window:
        ax.axvspan(window[0], window[1], color=WINDOW_COLOUR, zorder=0, linewidth=0)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel(label)
    ax.grid(True, which="major", alpha=0.3)
    figures.legend_right(ax, title=f"{short}: err ∝ t$^p$, p ± 95 %\nfitted over the shaded window")


def figure(report, scene, palette):
    """horizon-<scene>.png: energy error (top), rotation defect, then each first integral's error the scene
    declares, against t, log-log."""
    entries = [r for r in runs(report, scene) if r.get("t")]
    if not entries:
        raise figures.NothingToPlot(f"no horizon runs for scene {scene}")
    names = invariant_names(entries)
    panels = [(entries, key, label, short) for key, label, short in SERIES]
    panels += [([invariant_view(r, n) for r in entries], INVARIANT + n,
                "|I − I$_0$| / start magnitude, largest per window", n) for n in names]
    fig = figures.new_figure(11, 4.75 * len(panels))
    axes = fig.subplots(len(panels), 1)
    first = entries[0]
    for ax, (shown, key, label, short) in zip(axes, panels):
        _panel(ax, shown, key, label, short, palette)
        ax.set_title(f"{scene} ({kind(first)}): {short}{' error' if key.startswith(INVARIANT) else ''} over "
                     f"{count_text(first.get('steps_planned'))} steps of h = {rp.num(first.get('h')):g} s",
                     fontsize=10)
    fig.subplots_adjust(hspace=0.3)
    return fig


def section(report):
    """summary.md's "Long horizons": per scene and method the fitted exponents and the errors at the end."""
    lines = [HEADING, ""]
    entries = runs(report)
    if not entries:
        return lines + ["The report has no horizon study (`rollbench run --horizon-steps N`, or the default and "
                        "full presets).", ""]
    fit = fit_of(entries[0], "energy_error")
    t_from, t_to = rp.num(fit.get("t_from")), rp.num(fit.get("t_to"))
    decades = f"{math.log10(t_to / t_from):g}" if t_from > 0 and t_to > t_from else "—"
    spread = rp.num(((report.get("options") or {}).get("horizon") or {}).get("asymptotic_spread"))
    spread_text = f" by more than {spread:g}" if math.isfinite(spread) else ""
    lines += ["Growth of the energy error and of the rotation defect ‖RᵀR − I‖_F over long fixed-step runs, each "
              "as its envelope (the largest value in each log-spaced window between samples): the exponent p "
              "of err ≈ C tᵖ by least squares on log-log over "
              f"t = {md.fmt(t_from)} – {md.fmt(t_to)} s (the last {decades} "
              "decades of the run), ± its 95 % interval, and the slopes over the first and second half of that "
              f"window (early → late). Where they differ{spread_text}, the growth law is still changing and "
              "p reads \"not yet asymptotic (early → late)\". p ≈ 0: bounded, 1: a steady drift, 2: a drift "
              "that feeds on itself, ½: a random walk. \"rounding\": the largest value in the window is below "
              "100 ε √n (times the energy scale for the energy), rounding errors and not the method. A run that "
              "stopped has no fit. \"same as\": the series equals an earlier run's to 1e-9 relative at every "
              "sample (the same tableau on (v, α) of a homogeneous ball), drawn and stated once.", ""]
    rows = []
    for r in entries:
        e, d = fit_of(r, "energy_error"), fit_of(r, "rotation_defect")
        stopped = r.get("status", "ok") != "ok"
        last_e = (r.get("energy_error") or [None])[-1]
        last_d = (r.get("rotation_defect") or [None])[-1]
        rows.append([r["scene"], kind(r), r["integrator"],
                     r.get("status", "ok") + (f" at t = {md.fmt(rp.num(r.get('stop_time')))}" if stopped else ""),
                     count_text(r.get("steps")),
                     exponent_text(e), halves_text(e), md.fmt(rp.num(last_e)),
                     exponent_text(d), halves_text(d), md.fmt(rp.num(last_d)), md.fmt(rp.num(r.get("wall_s"))),
                     _same_text(r)])
    lines += md.table(["scene", "kind", "integrator", "status", "steps", "energy p", "early → late",
                       "energy error at the end (J)", "defect p", "early → late", "defect at the end",
                       "wall s", "same as"], rows)
    lines += _invariant_table(entries)
    total = sum(rp.num(r.get("wall_s")) for r in entries if math.isfinite(rp.num(r.get("wall_s"))))
    return lines + ["", f"The study took {total:.1f} s of wall time ({len(entries)} runs).", ""]


def _invariant_table(entries):
    """The first integrals' errors, as the energy's: per scene, method and integral."""
    rows = []
    for r in entries:
        for name in invariant_names([r]):
            view = invariant_view(r, name)
            f = fit_of(view, INVARIANT + name)
            rows.append([r["scene"], r["integrator"], name, exponent_text(f), halves_text(f),
                         md.fmt(rp.num((view[INVARIANT + name] or [None])[-1])),
                         same_as(view, INVARIANT + name) or "—"])
    if not rows:
        return []
    intro = ("First integrals beyond the energy that the scene declares (docs/model.md, \"Invariants beyond the "
             "energy\"): each one's error |I − I₀| relative to its magnitude at the start (the sum of its terms' "
             "absolute values), its envelope fitted as the energy's; \"rounding\": below 100 ε √n.")
    return ["", INVARIANT_HEADING, "", intro, ""] + md.table(
        ["scene", "integrator", "integral", "p", "early → late", "relative error at the end", "same as"], rows)


def _same_text(run):
    """'energy: rk4; defect: rk4', or '—'."""
    series = (("energy_error", "energy"), ("rotation_defect", "defect"))
    parts = [f"{short}: {same_as(run, key)}" for key, short in series if same_as(run, key)]
    return "; ".join(parts) or "—"


def _names(items):
    return ", ".join(f"{n} {p:.2f}" for n, p in items)


def _exponents(entries, done, key):
    """(asymptotic [(p, name)], rounding names, not asymptotic [name (early → late)]) of one series, each
    shared series once under all its names."""
    steady, rounding, moving = [], [], []
    for r in done:
        fit = fit_of(r, key)
        p = rp.num(fit.get("p"))
        if same_as(r, key):
            continue
        name = shown_name(entries, r, key)
        if fit.get("at_rounding"):
            rounding.append((p, name))
        elif not math.isfinite(p):
            continue
        elif not_asymptotic(fit):
            moving.append(f"{name} ({halves_text(fit)})")
        else:
            steady.append((p, name))
    return sorted(steady), rounding, moving


def _invariant_parts(entries, done):
    """Per first integral: the range of its exponents, who keeps it at rounding, whose fit still moves."""
    parts = []
    for name in invariant_names(entries):
        views = [invariant_view(r, name) for r in done]
        steady, rounding, moving = _exponents(views, views, INVARIANT + name)
        if len(steady) == 1:
            parts.append(f"{name} error ∝ tᵖ with p = {steady[0][0]:.2f} ({steady[0][1]})")
        elif steady:
            parts.append(f"{name} error ∝ tᵖ with p from {steady[0][0]:.2f} ({steady[0][1]}) to "
                         f"{steady[-1][0]:.2f} ({steady[-1][1]})")
        if rounding:
            parts.append(f"{name} at rounding for {', '.join(n for _, n in rounding)}")
        if moving:
            parts.append(f"{name} not yet asymptotic (p early → late) for {', '.join(moving)}")
    return parts


def finding_lines(report):
    """One line per scene for the findings: the energy exponents (or that they are not yet asymptotic), who
    keeps R at rounding, who stopped; series identical by construction once, under all their names."""
    lines = []
    for scene in scenes(report):
        entries = runs(report, scene)
        first = entries[0]
        done = [r for r in entries if r.get("status", "ok") == "ok"]
        energy, energy_rounding, energy_moving = _exponents(entries, done, "energy_error")
        energy = sorted(energy + [(p, f"{n}, rounding") for p, n in energy_rounding if math.isfinite(p)])
        growing, rounding, defect_moving = _exponents(entries, done, "rotation_defect")
        stopped = [f"{r['integrator']} ({r.get('status')} at t = {md.fmt(rp.num(r.get('stop_time')))})"
                   for r in entries if r.get("status", "ok") != "ok"]
        parts = []
        if energy:
            parts.append(f"energy error ∝ tᵖ with p from {energy[0][0]:.2f} ({energy[0][1]}) to "
                         f"{energy[-1][0]:.2f} ({energy[-1][1]})")
        if energy_moving:
            parts.append(f"energy error not yet asymptotic (p early → late) for {', '.join(energy_moving)}")
        if growing:
            parts.append(f"rotation defect grows for {_names((n, p) for p, n in growing)}")
        if defect_moving:
            parts.append(f"rotation defect not yet asymptotic (p early → late) for {', '.join(defect_moving)}")
        if rounding:
            parts.append(f"stays at rounding for {', '.join(n for _, n in rounding)}")
        if stopped:
            parts.append(f"stopped: {', '.join(stopped)}")
        shared = [shown_name(entries, r, key) for key in ("energy_error",) for r in done
                  if not same_as(r, key) and " = " in shown_name(entries, r, key)]
        if shared:
            parts.append("identical energy series (one tableau stepping (v, α)): " + "; ".join(shared))
        parts += _invariant_parts(entries, done)
        lines.append(f"- Long horizon on {scene} ({kind(first)}, {count_text(first.get('steps_planned'))} steps of "
                     f"h = {rp.num(first.get('h')):g} s): " + ("; ".join(parts) or "no run reached the end") + ".")
    return lines

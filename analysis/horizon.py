"""The horizon study (docs/usage.md#the-horizon-study): horizon-<scene>.png,
the energy error and the rotation defect (their envelope: the largest in
each log-spaced window) against t on log-log axes with the runner's growth
class (bounded, linear, quadratic, power, exponential, rounding) and
exponent p of err ~ C t^p in the legend; the "Long horizons" section of
summary.md and its line in the findings. A class the runner left
"undecided" (its per-decade slopes still moving over the last three
decades, bench/lib/growth_class.hpp) reads "undecided at N steps" with the
slopes, never a p, and is never compared: the findings compare decided
classes only. A fit from a report older than the classes is undecided (its
two-decade window decided too early, issue 56). A series the report marks
the same as an earlier run's (`same_as`) is drawn and stated once, under
both names. A
scene that declares first integrals beyond the energy (the runs'
`invariants`: Routh's, the Chaplygin ball's) gets one more panel per
integral, its relative error drawn and fitted the same way, and its own
table and findings; a kinematic integral (the runs' `kind`: kept by every
method by the form of the equations, docs/model.md#which-integrals-show-structure)
is drawn and tabulated, marked, but never cited in the findings. The energy
error is the one at the nearest rotation (`energy_error_on_group`) where the
report has it, the flat one in older reports."""
import math

import numpy as np

from analysis import figures
from analysis import markdown as md
from analysis import report as rp

HEADING = "## Long horizons"
INVARIANT_HEADING = "### First integrals beyond the energy"
# (key in a run and in its fit, axis label, short name)
SERIES = (("energy_error", "energy error |H(polar R) − H$_0$| (J), largest per window", "energy error"),
          ("rotation_defect", "rotation defect ‖R$^T$R − I‖$_F$, largest per window", "rotation defect"))
WINDOW_COLOUR = "#eeeeee"


def runs(report, scene=None):
    """The horizon study's runs of a report ([] for a report without the study), of one scene when given: the
    runs at the study's step, whose growth the figures and findings read (not the price runs)."""
    return [r for r in all_runs(report, scene) if coarsening(r) == 1]


def all_runs(report, scene=None):
    """Every horizon run, the price runs at k h (`coarsening` k > 1) too, of one scene when given, each with
    the energy error at the nearest rotation under `energy_error` (energy_view)."""
    return [energy_view(r) for r in rp.section_entries(report, "horizon.runs")
            if scene is None or r["scene"] == scene]


ON_GROUP = "energy_error_on_group"


def energy_view(run):
    """The run with its energy error at the nearest rotation, H(polar(R), v, α) (series, fit and twin), under
    `energy_error`, so that everything that draws, fits and states the energy reads it: the flat H hides R's
    drift off SO(3) (docs/model.md#how-the-energy-error-is-measured). A report without it is returned as it is
    (the flat energy error)."""
    if ON_GROUP not in run:
        return run
    view = dict(run)
    view["energy_error_flat"] = run.get("energy_error")
    view["energy_error"] = run.get(ON_GROUP)
    fit = dict(run.get("fit") or {})
    if ON_GROUP in fit:
        fit["energy_error"] = fit[ON_GROUP]
    view["fit"] = fit
    same = dict(run.get("same_as") or {})
    if ON_GROUP in same:
        same["energy_error"] = same[ON_GROUP]
    view["same_as"] = same
    return view


KINEMATIC = "kinematic"


def is_kinematic(entries, name):
    """Whether the runs mark the integral kinematic (kept by every method: never evidence of structure)."""
    return any(i.get("kind") == KINEMATIC for r in entries for i in (r.get("invariants") or [])
               if i.get("name") == name)


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


UNDECIDED = "undecided"
ROUNDING = "rounding"
# the classes that grow (bench/lib/growth_class.hpp); bounded and rounding do not
GROWING = ("linear", "quadratic", "power", "exponential")


def growth_class(fit):
    """The runner's class of a fit ('bounded', 'linear', 'quadratic', 'power', 'exponential', 'rounding',
    'undecided'), or None without one (a run that stopped). A fit from a report older than the classes is
    'rounding' where its window was at rounding, else 'undecided' where it has a p."""
    if "class" in fit:
        return fit["class"] if isinstance(fit["class"], str) else None
    if fit.get("at_rounding"):
        return ROUNDING
    return UNDECIDED if math.isfinite(rp.num(fit.get("p"))) else None


def decided(fit):
    """A class other than undecided: the only ones the findings compare."""
    return growth_class(fit) not in (None, UNDECIDED)


def slopes_text(fit):
    """The slopes over the decades of the fit's window, oldest first: '0.49, 0.63, 0.77' ('' without)."""
    t_from = rp.num(fit.get("t_from"))
    slopes = [rp.num(d.get("p")) for d in fit.get("decades") or []
              if isinstance(d, dict) and not rp.num(d.get("t_from")) < t_from * (1 - 1e-9)]
    return ", ".join(f"{p:.2f}" if math.isfinite(p) else "—" for p in slopes)


def steps_text(run):
    """'1,000,000 steps': the steps of the run the class was read from."""
    return f"{count_text(run.get('steps_planned'))} steps"


def undecided_text(fit, run):
    """'undecided at 1,000,000 steps (0.49, 0.63, 0.77)'."""
    slopes = slopes_text(fit)
    return f"undecided at {steps_text(run)}" + (f" ({slopes})" if slopes else "")


def exponent_text(fit, run=None):
    """'1.02 ± 0.02' (a decided class), '0.45 ± 0.06 (rounding)', 'rounding', 'undecided at N steps (0.49, 0.63,
    0.77)', or '—'."""
    p, ci = rp.num(fit.get("p")), rp.num(fit.get("ci95"))
    c = growth_class(fit)
    if c is None:
        return "—"
    if c == UNDECIDED:
        return undecided_text(fit, run or {})
    if not math.isfinite(p):
        return c
    text = f"{p:.2f} ± {ci:.2f}" if math.isfinite(ci) else f"{p:.2f}"
    return text + (" (rounding)" if c == ROUNDING else "")


def class_text(fit):
    """'linear (0.98, 1.00, 1.01)': the class and the per-decade slopes it was read from; 'undecided (…)'; '—'."""
    c = growth_class(fit)
    if c is None:
        return "—"
    slopes = slopes_text(fit)
    return c + (f" ({slopes})" if slopes and c != ROUNDING else "")


def same_as(run, key):
    """The integrator whose series this run's equals (the report's `same_as`), or None."""
    return (run.get("same_as") or {}).get(key)


def shown_name(entries, run, key):
    """'rk4 = rkmk4 = cf4' for a run whose series others share, else its name."""
    twins = [r["integrator"] for r in entries if same_as(r, key) == run["integrator"]]
    return " = ".join([run["integrator"]] + twins)


def count_text(value):
    """10000 -> '10,000'; '—' for a missing count."""
    return f"{value:,}" if isinstance(value, int) else "—"


def kind(run):
    return "R feeds back" if run.get("r_feeds_back") else "homogeneous"


def study_steps(run):
    """The steps the study asked for (`study_steps`; `steps_planned` in reports older than further decades)."""
    n = run.get("study_steps")
    return n if isinstance(n, int) else run.get("steps_planned")


def study_steps_text(entries):
    """'1,000,000 steps', or '1,000,000 steps (undecided runs on to 10,000,000)' where a run went on."""
    first = study_steps(entries[0])
    most = max((r.get("steps_planned") for r in entries if isinstance(r.get("steps_planned"), int)), default=first)
    text = f"{count_text(first)} steps"
    if isinstance(first, int) and isinstance(most, int) and most > first:
        text += f" (undecided runs on to {count_text(most)})"
    return text


def budget_note(run):
    """Why the study did not run an undecided class's next decade (the report's `budget_reason`), or None."""
    why = run.get("budget_reason")
    return why if run.get("budget_ran_out") and isinstance(why, str) else None


def _legend_label(entries, run, key):
    status = run.get("status", "ok")
    if status != "ok":
        return f"{run['integrator']}: {status} at t = {rp.num(run.get('stop_time')):.3g}"
    fit = fit_of(run, key)
    c, text = growth_class(fit), exponent_text(fit, run)
    if c in GROWING or c == "bounded":
        text = f"{c}, p = {text}"
    elif c == ROUNDING and math.isfinite(rp.num(fit.get("p"))):
        text = f"p = {text}"
    return f"{shown_name(entries, run, key)}: {text}"


def _fitted_line(window, log10_c, p):
    """The fit C t^p at 20 times over the window (inf where a report's absurd exponent overflows)."""
    tt = np.geomspace(*window, 20)
    return tt, np.power(10.0, log10_c) * tt ** p


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
        if 0 < t_from <= t_to <= figures.PLOT_MAX:
            window = (t_from, t_to)
        if math.isfinite(p) and math.isfinite(c) and window and decided(fit):
            # the fitted line over its window, a decided class's only: thick and faint, under the data
            with np.errstate(over="ignore", under="ignore"):
                tt, yy = figures.positive(*_fitted_line(window, c, p))
            ax.plot(tt, yy, color=style["color"], linewidth=4, alpha=0.3, label="_fit", zorder=1)
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
    figures.legend_right(ax, title=f"{short}: class, err ∝ t$^p$, p ± 95 %\nover the shaded window (3 decades)")


def figure(report, scene, palette):
    """horizon-<scene>.png: energy error (top), rotation defect, then each first integral's error the scene
    declares, against t, log-log."""
    entries = [r for r in runs(report, scene) if r.get("t")]
    if not entries:
        raise figures.NothingToPlot(f"no horizon runs for scene {scene}")
    names = invariant_names(entries)
    panels = [(entries, key, label, short) for key, label, short in SERIES]
    panels += [([invariant_view(r, n) for r in entries], INVARIANT + n,
                "|I − I$_0$| / start magnitude, largest per window",
                n + (" (kinematic: kept by every method)" if is_kinematic(entries, n) else "")) for n in names]
    fig = figures.new_figure(11, 4.75 * len(panels))
    axes = fig.subplots(len(panels), 1)
    first = entries[0]
    for ax, (shown, key, label, short) in zip(axes, panels):
        _panel(ax, shown, key, label, short, palette)
        ax.set_title(f"{scene} ({kind(first)}): {short}{' error' if key.startswith(INVARIANT) else ''} over "
                     f"{study_steps_text(entries)} of h = {rp.num(first.get('h')):g} s", fontsize=10)
    fig.subplots_adjust(hspace=0.3)
    return fig


def section(report):
    """summary.md's "Long horizons": per scene and method the fitted exponents and the errors at the end."""
    lines = [HEADING, ""]
    entries = runs(report)
    if not entries:
        return lines + ["The report has no horizon study (`rollbench run --horizon-steps N`, or the default and "
                        "full presets).", ""]
    options = (report.get("options") or {}).get("horizon") or {}
    spread = rp.num(options.get("asymptotic_spread"))
    spread_text = f"{spread:g}" if math.isfinite(spread) else "0.15"
    lines += ["Growth of the energy error (H at the nearest rotation, H(polar(R), v, α), where the report has it: "
              "the flat H hides R's drift off SO(3)) and of the rotation defect ‖RᵀR − I‖_F over long fixed-step "
              "runs, each as its envelope (the largest value in each log-spaced window, 8 a decade), and its "
              "class: the exponent p of err ≈ C tᵖ by least squares on log-log over the last 3 decades of t, ± "
              "its 95 % interval, decided only where the slopes over those decades (the class column, oldest "
              f"first) agree to {spread_text}, the last decade's slope lies within the earlier decades' interval, "
              "and each decade's interval lies in the class's band: bounded p ≤ 0.25, linear 1 ± 0.25, quadratic "
              "2 ± 0.25, power between them, exponential for slopes rising tenfold a decade; \"rounding\": the "
              "largest value in the window is below 100 ε √n (times the energy scale for the energy), rounding "
              "errors and not the method. Otherwise the class is \"undecided at N steps\" with its slopes, and "
              "the study runs the next decade (10 N) where its budget allows (`--horizon-steps-max`, "
              "`--horizon-cpu-max`); no p is read from it. A run that stopped has no class. \"same as\": the "
              "series equals an earlier run's to 1e-9 relative at every sample (the same tableau on (v, α) of a "
              "homogeneous ball), drawn and stated once.", ""]
    rows = []
    for r in entries:
        e, d = fit_of(r, "energy_error"), fit_of(r, "rotation_defect")
        stopped = r.get("status", "ok") != "ok"
        last_e = (r.get("energy_error") or [None])[-1]
        last_d = (r.get("rotation_defect") or [None])[-1]
        rows.append([r["scene"], kind(r), r["integrator"],
                     r.get("status", "ok") + (f" at t = {md.fmt(rp.num(r.get('stop_time')))}" if stopped else ""),
                     count_text(r.get("steps")),
                     _p_column(e), class_text(e), md.fmt(rp.num(last_e)),
                     _p_column(d), class_text(d), md.fmt(rp.num(last_d)), md.fmt(_wall_seconds(r)),
                     _same_text(r)])
    lines += md.table(["scene", "kind", "integrator", "status", "steps", "energy p", "energy class (slopes a decade)",
                       "energy error at the end (J)", "defect p", "defect class (slopes a decade)",
                       "defect at the end", "wall s", "same as"], rows)
    budget = [f"- {r['integrator']} on {r['scene']} at {steps_text(r)}: {budget_note(r)}" for r in entries
              if budget_note(r)]
    if budget:
        lines += ["", "Undecided where the budget ended the study (the next decade not run):", ""] + budget
    lines += _invariant_table(entries)
    total = sum(_wall_seconds(r) for r in entries if math.isfinite(_wall_seconds(r)))
    return lines + ["", f"The study took {total:.1f} s of wall time ({len(entries)} runs"
                    + (f", {sum(len(_earlier(r)) for r in entries)} of them run again a decade on"
                       if any(_earlier(r) for r in entries) else "") + ").", ""]


def _p_column(fit):
    """The exponent of a decided class ('1.00 ± 0.01', '0.50 ± 0.01 (rounding)'); 'undecided'; '—'."""
    c = growth_class(fit)
    return UNDECIDED if c == UNDECIDED else exponent_text(fit)


def _earlier(run):
    """The shorter runs the study made before the record's own (`earlier_runs`), shortest first."""
    return [e for e in run.get("earlier_runs") or [] if isinstance(e, dict)]


def _wall_seconds(run):
    """The wall time of the record's run and of the shorter ones before it."""
    return rp.num(run.get("wall_s")) + sum(rp.num(e.get("wall_s")) for e in _earlier(run)
                                           if math.isfinite(rp.num(e.get("wall_s"))))


def _invariant_table(entries):
    """The first integrals' errors, as the energy's: per scene, method and integral."""
    rows = []
    for r in entries:
        for name in invariant_names([r]):
            view = invariant_view(r, name)
            f = fit_of(view, INVARIANT + name)
            kinematic = is_kinematic([r], name)
            rows.append([r["scene"], r["integrator"], name + (" (kinematic)" if kinematic else ""),
                         _p_column(f), class_text(f),
                         md.fmt(rp.num((view[INVARIANT + name] or [None])[-1])),
                         same_as(view, INVARIANT + name) or "—"])
    if not rows:
        return []
    intro = ("First integrals beyond the energy that the scene declares (docs/model.md, \"Invariants beyond the "
             "energy\"): each one's error |I − I₀| relative to its magnitude at the start (the sum of its terms' "
             "absolute values), its envelope classed as the energy's; \"rounding\": below 100 ε √n. "
             "\"kinematic\": every method keeps it by the form of the equations (a linear integral whose rate is "
             "identically 0, and R on SO(3)), so keeping it is no evidence of structure "
             "(docs/model.md#which-integrals-show-structure); the findings do not cite it.")
    return ["", INVARIANT_HEADING, "", intro, ""] + md.table(
        ["scene", "integrator", "integral", "p", "class (slopes a decade)", "relative error at the end", "same as"],
        rows)


def _same_text(run):
    """'energy: rk4; defect: rk4', or '—'."""
    series = (("energy_error", "energy"), ("rotation_defect", "defect"))
    parts = [f"{short}: {same_as(run, key)}" for key, short in series if same_as(run, key)]
    return "; ".join(parts) or "—"


def _names(items):
    return ", ".join(f"{n} {p:.2f}" for n, p in items)


def _exponents(entries, done, key, only=None):
    """(decided, growing or bounded [(p, name)], rounding [(p, name)], undecided ['name at N steps (slopes)'])
    of one series, each shared series once under all its names; only: the decided classes to list (all)."""
    steady, rounding, moving = [], [], []
    for r in done:
        fit = fit_of(r, key)
        p, c = rp.num(fit.get("p")), growth_class(fit)
        if same_as(r, key):
            continue
        name = shown_name(entries, r, key)
        if c == ROUNDING:
            rounding.append((p, name))
        elif c == UNDECIDED:
            slopes = slopes_text(fit)
            moving.append(f"{name} at {steps_text(r)}" + (f" ({slopes})" if slopes else ""))
        elif c is not None and math.isfinite(p) and (only is None or c in only):
            steady.append((p, name))
    return sorted(steady), rounding, moving


def _invariant_parts(entries, done):
    """Per first integral: the range of its exponents, who keeps it at rounding, whose fit still moves."""
    parts = []
    for name in invariant_names(entries):
        if is_kinematic(entries, name):
            continue  # kept by every method: no evidence of structure preservation, never cited
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
            parts.append(f"{name} undecided (slopes a decade) for {', '.join(moving)}")
    return parts


def finding_lines(report):
    """One line per scene for the findings: the exponents of the decided energy classes, the undecided ones with
    their slopes (never a p), whose rotation defect grows or stays bounded, who keeps R at rounding, who stopped,
    where the budget ended the study; series identical by construction once, under all their names."""
    lines = []
    for scene in scenes(report):
        entries = runs(report, scene)
        first = entries[0]
        done = [r for r in entries if r.get("status", "ok") == "ok"]
        energy, energy_rounding, energy_moving = _exponents(entries, done, "energy_error")
        energy = sorted(energy + [(p, f"{n}, rounding") for p, n in energy_rounding if math.isfinite(p)])
        growing, rounding, defect_moving = _exponents(entries, done, "rotation_defect", only=GROWING)
        bounded = _exponents(entries, done, "rotation_defect", only=("bounded",))[0]
        stopped = [f"{r['integrator']} ({r.get('status')} at t = {md.fmt(rp.num(r.get('stop_time')))})"
                   for r in entries if r.get("status", "ok") != "ok"]
        parts = []
        if energy:
            parts.append(f"energy error ∝ tᵖ with p from {energy[0][0]:.2f} ({energy[0][1]}) to "
                         f"{energy[-1][0]:.2f} ({energy[-1][1]})")
        if energy_moving:
            parts.append(f"energy error undecided (slopes a decade) for {', '.join(energy_moving)}")
        if growing:
            parts.append(f"rotation defect grows for {_names((n, p) for p, n in growing)}")
        if bounded:
            parts.append(f"rotation defect bounded for {', '.join(n for _, n in bounded)}")
        if defect_moving:
            parts.append(f"rotation defect undecided (slopes a decade) for {', '.join(defect_moving)}")
        if rounding:
            parts.append(f"stays at rounding for {', '.join(n for _, n in rounding)}")
        if stopped:
            parts.append(f"stopped: {', '.join(stopped)}")
        shared = [shown_name(entries, r, key) for key in ("energy_error",) for r in done
                  if not same_as(r, key) and " = " in shown_name(entries, r, key)]
        if shared:
            parts.append("identical energy series (one tableau stepping (v, α)): " + "; ".join(shared))
        parts += _invariant_parts(entries, done)
        budget = [r["integrator"] for r in entries if budget_note(r)]
        if budget:
            parts.append(f"the budget ended the study undecided for {', '.join(budget)}")
        lines.append(f"- Long horizon on {scene} ({kind(first)}, {study_steps_text(entries)} of "
                     f"h = {rp.num(first.get('h')):g} s): " + ("; ".join(parts) or "no run reached the end") + ".")
    return lines

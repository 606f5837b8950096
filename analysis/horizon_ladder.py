"""What keeps the energy bounded over a long horizon, and at what price (docs/usage.md#the-horizon-study; the ladder
of scenes in docs/model.md#invariants-beyond-the-energy). Per horizon scene, each method's energy error is
"bounded" (the runner's class bounded, p at most BOUNDED_P over three decades that agree, or rounding), "grows"
(a decided linear, quadratic, power or exponential class) or "undecided" (bench/lib/growth_class.hpp), and only
decided classes are compared: "bounded where symmetry alone grows" needs both decided. Each method is "symmetric"
when the sweep's
reversibility defects of all its runs are at rounding (analysis/reversibility.py), "explicit" when they are
not. The findings say per scene which symmetric methods keep the energy bounded, which do not, and the cheapest
run whose relative energy error stays under ENERGY_TARGET over the whole horizon, with its CPU time against rk4's
run at the study's step: the study's runs and the price runs (the same horizon at k h, `coarsening` k) all compete,
so a method that stays under at 16 h is priced there. Errors and CPU times are compared over the study's own
horizon: a run the study took on a decade further (undecided) is priced and compared by its first run
(`earlier_runs`). horizon-cost.png draws it: per scene, each method's runs (one point per step, joined) as CPU
seconds against the largest relative energy error, with the ENERGY_TARGET line."""
import math

from analysis import figures, horizon, reversibility
from analysis import markdown as md
from analysis import report as rp

# Bounded: an envelope that neither drifts (p = 1) nor random-walks (p = 1/2); halfway to the random walk (the
# runner's class band, GrowthRules::band).
BOUNDED_P = 0.25
# The relative energy error a long run must stay under (issue 34: "keep the energy error under 1e-6").
ENERGY_TARGET = 1e-6
BASELINE = "rk4"
COST_FIGURE = "horizon-cost.png"
# The variational method (dla2, docs/model.md#a-discrete-lagrangedalembert-method) and the discrete gradient, told
# apart from the other symmetric methods by family.
VARIATIONAL_FAMILY = "nonholonomic-variational"
DISCRETE_GRADIENT_FAMILY = "discrete-gradient"


def symmetric_methods(report):
    """The fixed-step methods whose every measured reversibility defect in the sweep is at rounding."""
    worst = {}
    for scene in rp.scenes(report):
        for name, (w, _) in reversibility.largest_defects(report, scene).items():
            worst[name] = max(worst.get(name, 0.0), w)
    return {n for n, w in worst.items() if w <= reversibility.AT_ROUNDING}


UNDECIDED = "undecided"


def energy_class(run):
    """'bounded', 'grows', 'undecided', or None (a run that stopped, or no fit): the runner's class."""
    if run.get("status", "ok") != "ok":
        return None
    c = horizon.growth_class(horizon.fit_of(run, "energy_error"))
    if c in ("bounded", horizon.ROUNDING):
        return "bounded"
    if c in horizon.GROWING:
        return "grows"
    return UNDECIDED if c == horizon.UNDECIDED else None


def _first_run(run):
    """The study's first run of a record the study took on a decade further (`earlier_runs`), else None."""
    earlier = [e for e in run.get("earlier_runs") or [] if isinstance(e, dict)]
    return earlier[0] if earlier else None


def relative_energy_error(run):
    """The largest energy error over the study's horizon relative to the energy scale (the record's run, or its
    first run where the study went on a decade: runs are compared over one horizon); inf for a run that stopped."""
    first = _first_run(run)
    if first is not None:
        largest = first.get("largest") or {}
        key = horizon.ON_GROUP if rp.num(largest.get(horizon.ON_GROUP)) >= 0 else "energy_error"
        scale = rp.num(run.get("energy_scale"))
        error = rp.num(largest.get(key))
        if first.get("status", "ok") != "ok":
            return math.inf
        return error / scale if math.isfinite(error) and scale > 0 else math.nan
    if run.get("status", "ok") != "ok":
        return math.inf
    errors = [rp.num(e) for e in run.get("energy_error") or []]
    scale = rp.num(run.get("energy_scale"))
    errors = [e for e in errors if math.isfinite(e)]
    return max(errors) / scale if errors and scale > 0 else math.nan


def cpu_seconds(run):
    """The CPU time of the run over the study's horizon (`cpu_s`; its first run's where the study went on a
    decade); its wall time for reports that predate it."""
    run = _first_run(run) or run
    cpu = rp.num(run.get("cpu_s"))
    return cpu if math.isfinite(cpu) else rp.num(run.get("wall_s"))


def _p_text(run):
    fit = horizon.fit_of(run, "energy_error")
    c = horizon.growth_class(fit)
    if c == horizon.ROUNDING:
        return "rounding"
    if c == horizon.UNDECIDED:
        return horizon.undecided_text(fit, run)
    return f"p = {rp.num(fit.get('p')):.2f}"


def _listed(runs):
    return ", ".join(f"{r['integrator']} ({_p_text(r)})" for r in runs)


def _range(ps):
    return f"p = {ps[0]:.2f}" if len(ps) == 1 or ps[0] == ps[-1] else f"p {ps[0]:.2f} – {ps[-1]:.2f}"


def _at_step(run):
    k = horizon.coarsening(run)
    return "" if k == 1 else f" at {k} h"


def _price(runs):
    """'cheapest under 1e-6: gauss2 at 4 h, 2.1 s CPU (3.0 × rk4's 0.7 s)' over a scene's study and price runs,
    or a sentence saying no run stays under."""
    under = [r for r in runs if relative_energy_error(r) <= ENERGY_TARGET and math.isfinite(cpu_seconds(r))]
    if not under:
        steps = sorted({horizon.coarsening(r) for r in runs})
        tried = ", ".join("h" if k == 1 else f"{k} h" for k in steps)
        return f"no run keeps the relative energy error under {ENERGY_TARGET:.0e} (steps {tried})"
    run = min(under, key=lambda r: (cpu_seconds(r), r["integrator"], horizon.coarsening(r)))
    cpu, name = cpu_seconds(run), run["integrator"]
    base = next((cpu_seconds(r) for r in runs if r["integrator"] == BASELINE and horizon.coarsening(r) == 1),
                math.nan)
    ratio = f" ({cpu / base:.1f} × {BASELINE}'s {md.fmt(base)} s at h)" if math.isfinite(base) and base > 0 else ""
    return (f"cheapest under {ENERGY_TARGET:.0e} relative energy error: {name}{_at_step(run)}, {md.fmt(cpu)} s "
            f"CPU{ratio}")


def finding_lines(report):
    """One line per horizon scene: which symmetric methods keep the energy bounded and which do not, the explicit
    ones' growth, and the price of staying under ENERGY_TARGET; then one line naming the scenes where symmetry
    alone kept every symmetric method's energy bounded."""
    symmetric = symmetric_methods(report)
    lines, held, failed = [], [], []
    for scene in horizon.scenes(report):
        entries = horizon.runs(report, scene)
        classes = [(r, energy_class(r)) for r in entries]
        sym = [(r, c) for r, c in classes if r["integrator"] in symmetric and c]
        if not sym:
            continue
        by = {kind: [r for r, c in sym if c == kind] for kind in ("bounded", "grows", UNDECIDED)}
        explicit = [r for r, c in classes if r["integrator"] not in symmetric and c == "grows"]
        if by["grows"]:
            failed.append(scene)
        elif not by[UNDECIDED]:
            held.append(scene)
        first = entries[0]
        parts = []
        for kind, text in (("bounded", "energy bounded for the symmetric "), ("grows", "growing for the symmetric "),
                           (UNDECIDED, "undecided for the symmetric ")):
            if by[kind]:
                parts.append(text + _listed(by[kind]))
        if explicit:
            ps = sorted(rp.num(horizon.fit_of(r, "energy_error").get("p")) for r in explicit)
            parts.append(f"growing for {len(explicit)} other method{'s' if len(explicit) > 1 else ''} ({_range(ps)})")
        parts.append(_price(horizon.all_runs(report, scene)))
        lines.append(f"- Ladder, {scene} ({horizon.kind(first)}, {horizon.study_steps_text(entries)}): "
                     + "; ".join(parts) + ".")
    if horizon.scenes(report) and not symmetric:
        lines.append("- Ladder: no method's reversibility defect was at rounding in this report's sweep (run the "
                     "horizon study's methods in the sweep too), so no line says what symmetry keeps.")
    if held or failed:
        lines.append(f"- Reversibility and the energy (decided classes only; bounded: p ≤ {BOUNDED_P} or rounding): "
                     "symmetry kept every "
                     "symmetric method's energy bounded on " + (", ".join(held) or "no scene")
                     + "; a symmetric method's energy grew on " + (", ".join(failed) or "no scene") + ".")
    return lines + variational_lines(report, symmetric)


def _with_error(r):
    return f"{r['integrator']} ({_p_text(r)}, {relative_energy_error(r):.1e})"


def _verdict(v, v_class, others):
    """What the variational run adds over the symmetric, non-variational runs of the same scene, and its key; only
    decided classes are compared (an undecided run on either side says so, never "bounded where ... grows")."""
    grown = [r for r, c in others if c == "grows"]
    held = [r for r, c in others if c == "bounded"]
    open_ = [r for r, c in others if c == UNDECIDED]
    names = ", ".join(r["integrator"] for r in (held if v_class != "bounded" else open_ or grown))
    if v_class == UNDECIDED:
        return "not compared: its class is undecided", "undecided"
    # a symmetric, non-variational method that stays bounded shows symmetry alone suffices on this scene, whatever
    # another one does: only where none does can the variational structure add boundedness, and only where every
    # one of them is decided can it be said that symmetry alone did not keep it
    if v_class == "bounded" and grown and not held and not open_:
        return f"it keeps the energy bounded where symmetry alone did not ({names})", "bounded"
    if v_class == "bounded" and open_ and not held:
        grew = f"; {', '.join(r['integrator'] for r in grown)} grow" if grown else ""
        return f"it keeps the energy bounded where symmetry alone is still undecided ({names}{grew})", "ahead"
    if v_class == "bounded":
        peers = [r for r in held if r.get("declared_order") == v.get("declared_order")] or held
        best = min(peers, key=relative_energy_error, default=None)
        if best is None:
            return "no symmetric, non-variational method to compare", "alone"
        ratio = relative_energy_error(v) / relative_energy_error(best)
        return (f"symmetry alone kept it bounded too ({', '.join(r['integrator'] for r in held)}): no boundedness "
                f"added, its largest error {ratio:.2g} × {best['integrator']}'s"), "nothing"
    if held:
        return f"it grows where symmetry alone kept it bounded ({names})", "worse"
    return "it grows, as the symmetric ones do", "grows"


def variational_lines(report, symmetric):
    """Per horizon scene with a variational (discrete Lagrange–d'Alembert) run: its energy class and largest error
    beside the symmetric methods that are not variational for this nonholonomic system and the discrete gradient,
    with what the variational structure adds and its CPU time against theirs; then one line over the scenes."""
    lines, verdicts = [], {}
    for scene in horizon.scenes(report):
        entries = horizon.runs(report, scene)
        classes = [(r, energy_class(r)) for r in entries]
        others = [(r, c) for r, c in classes if c and r["integrator"] in symmetric
                  and r.get("family") not in (VARIATIONAL_FAMILY, DISCRETE_GRADIENT_FAMILY)]
        gradient = [r for r, c in classes if c and r.get("family") == DISCRETE_GRADIENT_FAMILY]
        for v, v_class in classes:
            if v.get("family") != VARIATIONAL_FAMILY or not v_class:
                continue
            text, key = _verdict(v, v_class, others)
            verdicts.setdefault(key, []).append(scene)
            beside = [_with_error(r) for r, _ in others]
            cpu = ", ".join(f"{r['integrator']} {md.fmt(cpu_seconds(r))} s" for r in [v] + [r for r, _ in others]
                            + gradient)
            parts = [f"{v['integrator']}'s energy {_p_text(v)}, largest relative error "
                     f"{relative_energy_error(v):.1e}"]
            if beside:
                parts.append("symmetric, not variational: " + ", ".join(beside))
            if gradient:
                parts.append("discrete gradient: " + ", ".join(_with_error(r) for r in gradient))
            lines.append(f"- Variational structure, {scene}: " + "; ".join(parts) + f" — {text}; CPU {cpu}.")
    if verdicts:
        said = (("bounded", "bounded where symmetry alone was not on "),
                ("ahead", "bounded where symmetry alone is still undecided on "),
                ("nothing", "nothing beyond symmetry on "),
                ("worse", "growth where symmetry alone stayed bounded on "), ("grows", "growth like symmetry's on "),
                ("undecided", "undecided on "), ("alone", "no symmetric peer on "))
        lines.append("- What the variational structure adds to the energy (a discrete Lagrange–d'Alembert method "
                     "beside the symmetric, non-variational ones): "
                     + "; ".join(text + ", ".join(verdicts[key]) for key, text in said if key in verdicts) + ".")
    return lines


def cost_figure(report, palette):
    """horizon-cost.png: per horizon scene, CPU seconds per run against the largest relative energy error, the
    runs that stopped at the top edge."""
    names = horizon.scenes(report)
    if not names:
        raise figures.NothingToPlot("no horizon runs")
    cols = min(3, len(names))
    rows = math.ceil(len(names) / cols)
    fig = figures.new_figure(5.2 * cols, 4.2 * rows)
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax, scene in zip(axes, names):
        entries = horizon.runs(report, scene)
        by_method = {}
        for r in horizon.all_runs(report, scene):
            by_method.setdefault(r["integrator"], []).append(r)
        for name, runs in by_method.items():
            ok, stopped = [], []
            for r in runs:
                x, y = cpu_seconds(r), relative_energy_error(r)
                # a run without a time, or one that ran but recorded no finite error, has no point to draw
                if not (math.isfinite(x) and x > 0):
                    continue
                if r.get("status", "ok") != "ok":
                    stopped.append(x)
                elif math.isfinite(y):
                    ok.append((x, max(y, 1e-17)))
            style = palette.style(name)
            if ok:
                ok.sort()
                ax.plot([p[0] for p in ok], [p[1] for p in ok], markersize=6, label=name, linewidth=0.8, **style)
            if stopped:
                ax.plot(stopped, [1.0] * len(stopped), markersize=7, label=name + " (stopped)",
                        **dict(style, linestyle="none", marker="x"))
        ax.axhline(ENERGY_TARGET, color="#999999", linestyle=":", linewidth=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        first = entries[0]
        ax.set_title(f"{scene} ({horizon.kind(first)}), {horizon.count_text(first.get('steps_planned'))} steps",
                     fontsize=9)
        ax.set_xlabel("CPU s per run")
        ax.set_ylabel("largest |H − H₀| / energy scale")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes[len(names):]:
        ax.set_visible(False)
    shown = {}
    for ax in axes[:len(names)]:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            shown.setdefault(label, handle)
    legend_rows = math.ceil(len(shown) / 6)
    fig.legend(list(shown.values()), list(shown), loc="lower center", ncol=6, fontsize=7, frameon=False)
    # room for the x labels and the legend's rows, in inches of the figure's height
    fig.subplots_adjust(bottom=(0.75 + 0.2 * legend_rows) / fig.get_figheight(), hspace=0.4, wspace=0.3)
    fig.suptitle(f"The price of a bounded energy: one point per step (h and the price runs' coarser ones), the "
                 f"dotted line is {ENERGY_TARGET:.0e}; a stopped run sits at 1", fontsize=10)
    return fig

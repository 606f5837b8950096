"""summary.md: observed against declared orders with their verdicts, the
cost to reach given accuracies, same-tableau pairs, tolerance
proportionality, stability, long horizons and every failure."""
import math

import re

from analysis import answer, costs, findings, horizon, pairs, regime, stability
from analysis import markdown as md
from analysis import report as rp

VERDICTS = ("as declared", "lower", "exact", "inconclusive")


def _order_cell(order, component):
    value = rp.observed(order, component)
    if not math.isfinite(value):
        return "exact" if rp.verdict(order, component) == "exact" else "—"
    ci = (order.get("ci95") or {}).get(component)
    if isinstance(ci, list) and len(ci) == 2:
        # the interval itself, [low, high]
        low, high = rp.num(ci[0]), rp.num(ci[1])
        text = f"{value:.2f} [{low:.2f}, {high:.2f}]" if math.isfinite(low) and math.isfinite(high) else f"{value:.2f}"
    else:
        # the half-width
        ci = rp.num(ci)
        text = f"{value:.2f} ± {ci:.2f}" if math.isfinite(ci) else f"{value:.2f}"
    return f"{text} ({rp.verdict(order, component)})"


def overall_verdict(order, components):
    """'lower' if any component is lower, else 'inconclusive' if any is, else 'as declared' (exact
    components, which have no slope, count for neither; 'exact' when all are)."""
    found = [rp.verdict(order, c) for c in components if math.isfinite(rp.observed(order, c))]
    if not found:
        return "exact" if any(rp.verdict(order, c) == "exact" for c in components) else "—"
    if "lower" in found:
        return "**lower**"
    if all(v == "as declared" for v in found):
        return "as declared"
    return "inconclusive"


def orders_section(report):
    entries = rp.orders(report)
    lines = ["## Observed order", ""]
    if not entries:
        return lines + ["The report has no `orders` section (no fixed-step runs, or a quick preset).", ""]
    lines += ["Slope of log error against log h as the runner fitted it, its 95 % interval (± half-width, or "
              "[low, high]), and the runner's "
              "verdict per component: \"as declared\" when the interval lies within 0.2 of the declared order "
              "or above it, \"lower\" when below, \"exact\" when every step's error lies on the plateau (no slope "
              "to read), \"inconclusive\" when it is wider than ±0.3 or rests on fewer "
              "than 4 points (an inconclusive fit is no pass). Overall: lower if any component is lower, as "
              "declared only if all are.", ""]
    components = rp.components(report)
    rows = []
    for o in entries:
        declared, declared_rot = o.get("declared"), o.get("declared_rotation", o.get("declared"))
        fit = o.get("fit") or {}
        h_range = (f"{rp.num(fit.get('h_min')):.3g} – {rp.num(fit.get('h_max')):.3g}"
                   if math.isfinite(rp.num(fit.get("h_min"))) else "—")
        rows.append([o["scene"], o["integrator"], declared if declared is not None else "—",
                     declared_rot if declared_rot is not None else "—"]
                    + [_order_cell(o, c) for c in components] + [h_range, overall_verdict(o, components)])
    lines += md.table(["scene", "integrator", "declared", "declared (R)", *components, "fit range h (contact)",
                       "verdict"], rows)
    return lines + [""]


def tolerance_section(report):
    lines = ["## Tolerance proportionality", ""]
    fits = rp.tolerance_fits(report)
    if not fits:
        return lines + ["The report has no `tolerance_fits` (no adaptive runs).", ""]
    lines += ["Least-squares fit of log10 worst error against log10 tolerance per adaptive method, as the "
              "runner made it: slope 1 with a small residual means the tolerance means what it says; the "
              "intercept is log10 of the error at tolerance 1. \"step order\": the slope of log10 worst error "
              "against log10 mean step (t_end / steps), the observed order beside the declared one.", ""]
    declared = {}
    for r in rp.runs(report, adaptive=True):
        text = (r.entry.get("peer") or {}).get("declared_order_text")
        declared[(r.scene, r.integrator)] = text or (str(r.declared_order) if r.declared_order is not None else "—")

    def step_order(f):
        s = f.get("step_order") or {}
        slope, ci = rp.num(s.get("slope")), rp.num(s.get("ci95"))
        if not math.isfinite(slope):
            return "—"
        return f"{slope:.2f} ± {ci:.2f}" if math.isfinite(ci) else f"{slope:.2f}"
    rows = [[f["scene"], f["integrator"], declared.get((f["scene"], f["integrator"]), "—"), step_order(f),
             md.fmt(rp.num(f.get("slope"))), md.fmt(rp.num(f.get("intercept"))),
             md.fmt(rp.num(f.get("residual"))), f.get("points", "—")] for f in fits]
    return lines + md.table(["scene", "integrator", "declared", "step order", "slope", "intercept", "residual",
                             "points"], rows) + [""]


def stability_section(report):
    lines = ["## Stability", ""]
    entries = rp.stable_steps(report)
    if not entries:
        return lines + ["The report has no stability study.", ""]
    if stability.has_limits(entries):
        return lines + _stability_limits(entries)
    # a report of before the two limits: one largest stable step per entry
    bounds = entries[0].get("thresholds") or {}
    horizon = rp.num(entries[0].get("horizon"))
    lines += ["Largest step h such that this and every smaller tested step run to "
              + (f"t = {md.fmt(horizon)} s " if math.isfinite(horizon) else "the study's end ")
              + "without failing: a run fails when it stops (its status), when its energy error passes "
              f"{md.fmt(rp.num(bounds.get('energy')))} of the energy scale, when ‖RᵀR − I‖_F passes "
              f"{md.fmt(rp.num(bounds.get('rotation_defect')))} (R is no rotation any more), or when either "
              "grows exponentially (over the last two doublings of time its envelope's slope on log-log "
              f"reaches {md.fmt(rp.num(bounds.get('growth_exponent')))} and accelerates). The energy error "
              "(of the scale; at the nearest rotation, H(polar(R), v, α), where the report has it) and the "
              "rotation defect at that step are its accuracy, shown beside the verdict "
              "and not used for it; \"none\": no tested step passes. Where a larger step failed, how the "
              "first one did (`chart-limit`: a Lie step past the exponential chart's edge).", ""]
    rows = []
    for e in entries:
        h = rp.stable_h(e)
        tested = rp.tested_h(e)
        tested = [t for t in tested if math.isfinite(t)]
        span = f"{min(tested):.3g} – {max(tested):.3g} ({len(tested)})" if tested else "—"
        rows.append([e["scene"], e["integrator"], md.fmt(h) if math.isfinite(h) else "none",
                     md.fmt(rp.num(e.get("rotation_defect"))),
                     # at the nearest rotation where recorded: the flat H hides R's drift off SO(3)
                     md.fmt(rp.num(e.get("energy_error_on_group", e.get("energy_error")))), span,
                     _first_failure(e, bounds)])
    return lines + md.table(["scene", "integrator", "largest stable h (s)", "rotation defect there",
                             "energy error there (of the scale)", "tested h (count)", "next step fails by"],
                            rows) + [""]


def _stability_limits(entries):
    """The blow-up step and h*(T) per horizon of each method and scene (analysis/stability.py)."""
    bounds = entries[0].get("thresholds") or {}
    times = stability.horizons(entries)
    lines = ["Two limits per fixed-step method and scene, read on a ladder of steps run from the largest down to "
             "the first that keeps every bound to the last horizon, each step one run to the last horizon read at "
             "each on its way. The **blow-up step**: the smallest step whose run fails by T — it stops (its "
             "status: a non-finite state, the solver failing, or a physical stop, which the numerics cause on "
             f"these bounded scenes), or its energy error passes {md.fmt(rp.num(bounds.get('blow_up_energy')))} × "
             f"the energy scale or ‖RᵀR − I‖_F passes {md.fmt(rp.num(bounds.get('blow_up_defect')))} (where no "
             "bounded motion goes) — before it drifts out of the bounds below or within "
             f"{md.fmt(rp.num(bounds.get('blow_up_steps')))} steps of it: the step's own exponential growth. A run "
             "that drifts out first and fails later fails of its drift, so the blow-up step is the same at every "
             "horizon unless a step fails only late with no drift before it (\"≤\": every step tried blew up; "
             "\">\": none did, the ladder's top). The **drift-limited step** h*(T): the largest step whose run "
             "to T, with every smaller step tried, keeps the energy error (at the nearest rotation, "
             f"H(polar(R), v, α), of the scale) within {md.fmt(rp.num(bounds.get('energy')))} and ‖RᵀR − I‖_F "
             f"within {md.fmt(rp.num(bounds.get('rotation_defect')))} and does not blow up; beside it what ended "
             "the next step, the quantity that crossed first with its largest value (over the run up to T, or up "
             "to where the study ended it) or its blow-up (\"≥\": the ladder's top kept them; \"none\": not "
             "even the smallest step tried). A drift that grows as a power of t moves h*(T) with T; no step whose "
             "energy error passes its bound counts.", ""]
    rows = []
    for e in entries:
        tested = [t for t in rp.tested_h(e) if math.isfinite(t)]
        span = f"{min(tested):.3g} – {max(tested):.3g} ({len(tested)})" if tested else "—"
        cells = []
        for t in times:
            d = stability.drift_at(e, t)
            cells.append(stability.drift_text(d) if d else "—")
        rows.append([e["scene"], e["integrator"], stability.blow_up_text(e)] + cells + [span])
    return lines + md.table(["scene", "integrator", "blow-up step (s)"]
                            + [f"h*({stability.seconds(t)}) (s)" for t in times] + ["tested h (count)"], rows) + [""]


def _first_failure(entry, bounds):
    """How the first unstable rung failed (the report's `failure`), with the numbers that decided it."""
    for t in entry.get("tried") or []:
        if t.get("stable", True):
            continue
        at = f"(h = {md.fmt(rp.num(t.get('h')))})"
        failure = t.get("failure")
        growth = t.get("growth") or {}
        if failure == "energy":
            return (f"energy error {md.fmt(rp.num(t.get('energy_error')))} > "
                    f"{md.fmt(rp.num(bounds.get('energy')))} of the scale {at}")
        if failure == "rotation-defect":
            return (f"rotation defect {md.fmt(rp.num(t.get('rotation_defect')))} > "
                    f"{md.fmt(rp.num(bounds.get('rotation_defect')))} {at}")
        if failure in ("energy-growth", "defect-growth"):
            key, name = (("energy_error", "energy error") if failure == "energy-growth"
                         else ("rotation_defect", "rotation defect"))
            g = growth.get(key) or {}
            return (f"exponential growth of the {name} (slope {md.fmt(rp.num(g.get('p_early')))} → "
                    f"{md.fmt(rp.num(g.get('p_late')))}) {at}")
        return f"{t.get('status', 'ok')} {at}"
    return "— (stable to the top)" if entry.get("at_limit") else "—"


def failures_section(report):
    lines = ["## Failures", ""]
    rows = []
    for r in rp.runs(report):
        if not rp.ok(r):
            rows.append([r.scene, r.integrator, rp.setting(r), r.status, md.fmt(r.stop_time), r.message])
    for d in rp.drift_runs(report):
        if d.get("status", "ok") != "ok":
            rows.append([d["scene"], d["integrator"] + " (drift run)", f"h={rp.num(d.get('h')):.6g}",
                         d["status"], md.fmt(rp.num(d.get("stop_time"))), d.get("message") or ""])
    for d in horizon.all_runs(report):
        if d.get("status", "ok") != "ok":
            price = f", {horizon.coarsening(d)} h" if horizon.coarsening(d) > 1 else ""
            rows.append([d["scene"], d["integrator"] + f" (horizon run{price})", f"h={rp.num(d.get('h')):.6g}",
                         d["status"], md.fmt(rp.num(d.get("stop_time"))), d.get("message") or ""])
    if not rows:
        return lines + ["No run failed.", ""]
    lines += md.table(["scene", "integrator", "setting", "status", "stopped at t", "message"], rows)
    return lines + [""]


def header_section(report, metric):
    machine = report.get("machine") or {}
    build = report.get("build") or {}
    lines = [f"- created: {report.get('created', '—')}, commit {report.get('git', '—')}, "
             f"preset {report.get('preset', '—')}",
             f"- machine: {machine.get('cpu', '—')}, {machine.get('cores', '—')} cores, {machine.get('os', '—')}",
             f"- build: {build.get('compiler', '—')} {build.get('type', '')}"
             + (f" `{build['flags']}`" if build.get("flags") else ""),
             f"- runs: {len(rp.runs(report))}, scenes: {', '.join(rp.scenes(report)) or '—'}",
             f"- accuracy metric of the cost tables: {metric} ({rp.metric_label(report, metric)}), read from each "
             f"run's `{rp._error_key}`" + (" (at t_end)" if rp._error_key == "error"
                                           else " (the largest over the timed run's steps)"), ""]
    refs = rp.section_entries(report, "references")
    if refs:
        rows = [[r["scene"], r.get("kind", "—"), r.get("method", "—"), r.get("cross_check", "—"),
                 md.fmt(rp.num(r.get("error")))] for r in refs]
        lines += ["## References", ""]
        lines += md.table(["scene", "kind", "method", "cross-check", "own error"], rows) + [""]
    return lines


def slug(heading):
    """The anchor of a heading: lower case, words joined by '-' (what index.html's ids are)."""
    return re.sub(r"[^a-z0-9]+", "-", heading.lower()).strip("-")


CONTENTS = "## Contents"


def contents(lines):
    """A list of links to the level-2 sections in lines."""
    heads = [line[3:] for line in lines if line.startswith("## ")]
    return [CONTENTS, ""] + [f"- [{h}](#{slug(h)})" for h in heads] + [""]


def failure_counts(report):
    """'N ok, M diverged, ...' over the runs: every status named as the runner wrote it."""
    counts = {}
    for r in rp.runs(report):
        counts[r.status] = counts.get(r.status, 0) + 1
    return ", ".join(f"{n} {s}" for s, n in sorted(counts.items(), key=lambda x: (x[0] != "ok", -x[1])))


def summary_markdown(report, metric=rp.DEFAULT_METRIC):
    # the answer, then answer.png (plot.py draws it from the same cells), then the definitions
    top = ["# rollbench summary", ""] + findings.findings_section(report, metric, figure=answer.figure_lines())
    body = (header_section(report, metric) + regime.regime_section(report, metric) + orders_section(report)
            + costs.cost_section(report, metric)
            + pairs.pairs_section(report, metric) + tolerance_section(report) + stability_section(report)
            + horizon.section(report) + failures_section(report))
    provenance = ["## Provenance", ""] + body[:body.index("")] + [f"- run statuses: {failure_counts(report)}", ""]
    body = provenance + body[body.index("") + 1:]
    lines = top + contents(body) + body
    return "\n".join(lines).rstrip() + "\n"

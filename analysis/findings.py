"""summary.md's and index.html's first section, "## Findings": the answers
before the evidence. Per scene: whether R feeds back into the motion, the
cheapest method at each target accuracy, and for every same-tableau
flat/Lie pair the flat/Lie time ratio with its spread over the timed
repeats; then what the order study could and could not decide."""
import math

from analysis import costs, horizon, pairs, regime
from analysis import markdown as md
from analysis import report as rp

HEADING = "## Findings"


def scene_kind(report, scene):
    """'R feeds back' (anisotropic ball, with its moments), 'homogeneous', or 'unknown' (an older report)."""
    ref = rp.reference(report, scene) or {}
    if "r_feeds_back" not in ref:
        return "unknown"
    if not ref["r_feeds_back"]:
        return "homogeneous"
    inertia = ref.get("inertia") or []
    moments = ", ".join(f"{rp.num(i):.3g}" for i in inertia)
    return f"R feeds back (moments {moments} kg m²)" if moments else "R feeds back"


def feeds_back(report, scene):
    return bool((rp.reference(report, scene) or {}).get("r_feeds_back"))


def ratio_text(ratio):
    median, low, high, repeats, bound = ratio
    if not math.isfinite(median):
        return "—"
    text = f"{bound} {median:.2f}".strip()
    if repeats > 1:
        text += f" [{low:.2f}–{high:.2f}]"
    return text


def pair_ratios(report, scene, metric):
    """[(flat, lie, tableau, {target: ratio})] of a scene (pairs.time_ratio)."""
    runs = rp.runs(report, scene)
    floor = rp.floor(report, scene)
    return [(flat, lie, tableau, {t: pairs.time_ratio(runs, flat, lie, metric, floor, t) for t in costs.TARGETS})
            for flat, lie, tableau in pairs.tableau_pairs(runs)]


def _cheapest_cell(table, target):
    reached = [(cells[("time", target)], name) for name, cells in table.items()
               if math.isfinite(cells[("time", target)][0])]
    if not reached:
        return "— (no method gets there)"
    (cost, bound), name = min(reached)
    return f"{name} ({md.fmt(cost, bound)} s)"


def _verdict_counts(report):
    """(verdicts, inconclusive, {reason: count}) over every component of every fixed-step fit."""
    total, inconclusive, reasons = 0, 0, {}
    for o in rp.orders(report):
        for c in rp.components(report):
            v = rp.verdict(o, c)
            if v == "—":
                continue
            total += 1
            if v == "inconclusive":
                inconclusive += 1
                why = (o.get("inconclusive_reason") or {}).get(c) or "not given"
                reasons[why] = reasons.get(why, 0) + 1
    return total, inconclusive, reasons


def order_lines(report):
    total, inconclusive, reasons = _verdict_counts(report)
    if not total:
        return []
    why = ", ".join(f"{n} {r}" for r, n in sorted(reasons.items(), key=lambda x: (-x[1], x[0])))
    lines = [f"- Orders: {total - inconclusive} of {total} component fits reach a verdict; {inconclusive} are "
             f"inconclusive" + (f" ({why})" if why else "") + ". \"too few points\": under 4 in the window; "
             "\"floor\": as few because the runs reached 10 × the reference's error; \"wide interval\": 95 % "
             "half-width above 0.3; \"straddles\": the interval holds declared − 0.2."]
    high = {}
    for o in rp.orders(report):
        if (o.get("declared") or 0) >= 8 and feeds_back(report, o["scene"]):
            decided = [c for c in rp.components(report) if rp.verdict(o, c) in ("as declared", "lower")]
            high.setdefault(o["integrator"], []).append(f"{o['scene']} {len(decided)}/{len(rp.components(report))}")
    if high:
        lines.append("- Order-8 methods where R feeds back (components with a verdict): "
                     + "; ".join(f"{n}: {', '.join(v)}" for n, v in high.items()) + ".")
    return lines


def findings_section(report, metric=rp.DEFAULT_METRIC):
    lines = [HEADING, ""]
    scenes = [s for s in rp.scenes(report) if rp.runs(report, s)]
    if not scenes:
        return lines + ["No runs: nothing to find.", ""]
    targets = ", ".join(f"{t:.0e}" for t in costs.TARGETS)
    lines += [f"Which method is cheapest at a {metric} error of {targets}, and whether keeping R on SO(3) pays: "
              f"wall time to reach the target {costs.HOW}. A pair shares its Butcher tableau (the methods' "
              "`tableau`); its ratio is flat time / Lie time (above 1: the Lie method is cheaper), the median "
              "over the timed repeats with [lowest–highest] (repeat k reads every run's k-th timed sample); "
              "\"≤\"/\"≥\": a side's cheapest run is already there, so the ratio is a bound.", ""]
    summary, rows, pair_rows, unreached = [], [], [], 0
    for scene in scenes:
        kind = scene_kind(report, scene)
        table = costs.cost_rows(report, scene, metric)
        rows.append([scene, kind] + [_cheapest_cell(table, t) for t in costs.TARGETS])
        for flat, lie, tableau, ratios in pair_ratios(report, scene, metric):
            if not any(math.isfinite(ratios[t][0]) for t in costs.TARGETS):
                unreached += 1  # neither target reached by both: nothing to compare here
                continue
            pair_rows.append([scene, "R feeds back" if feeds_back(report, scene) else kind.split(" (")[0],
                              f"{flat} / {lie}", tableau] + [ratio_text(ratios[t]) for t in costs.TARGETS])
            for t in costs.TARGETS:
                median = ratios[t][0]
                if math.isfinite(median):
                    summary.append((feeds_back(report, scene), median))
    for where, label in ((True, "where R feeds back"), (False, "on homogeneous scenes")):
        values = sorted(m for w, m in summary if w == where)
        if values:
            cheaper = sum(1 for v in values if v > 1)
            lines.append(f"- Keeping R on SO(3) {label}: the Lie method is cheaper in {cheaper} of {len(values)} "
                         f"pair × target cells; flat/Lie time ratio {values[0]:.2f} to {values[-1]:.2f} "
                         f"(median {values[len(values) // 2]:.2f}).")
    if not summary:
        lines.append("- No same-tableau flat/Lie pair reached a target in this report.")
    lines += regime.findings_lines(report, metric) + order_lines(report) + horizon.finding_lines(report) + [""]
    lines += ["### Cheapest method by wall time", ""]
    lines += md.table(["scene", "kind"] + [f"{metric} error {t:.0e}" for t in costs.TARGETS], rows) + [""]
    if pair_rows:
        lines += ["### Same tableau: flat / Lie time ratio", ""]
        lines += md.table(["scene", "kind", "flat / Lie", "tableau"] + [f"ratio at {t:.0e}" for t in costs.TARGETS],
                          pair_rows) + [""]
    if unreached:
        lines += [f"{unreached} scene × pair combinations where no target is reached by both methods are left out "
                  "(the section \"Same tableau, flat vs Lie\" has their costs).", ""]
    return lines

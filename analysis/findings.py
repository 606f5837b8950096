"""summary.md's and index.html's first section, "## Findings": the answers
before the evidence. Per scene: whether R feeds back into the motion, the
cheapest method at each target accuracy, and for every same-tableau
flat/Lie pair the flat/Lie time ratio with its spread over the timed
repeats; then what the order study could and could not decide."""
import math

from analysis import answer, costs, frontier, horizon, horizon_ladder, pairs, regime, reversibility, stability
from analysis import markdown as md
from analysis import report as rp
from analysis.pairs import ratio_text

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
    """(verdicts, inconclusive, {reason: count}, {verdict: count}) over every component of every fixed-step fit."""
    total, inconclusive, reasons, kinds = 0, 0, {}, {}
    for o in rp.orders(report):
        for c in rp.components(report):
            v = rp.verdict(o, c)
            if v == "—":
                continue
            total += 1
            kinds[v] = kinds.get(v, 0) + 1
            if v == "inconclusive":
                inconclusive += 1
                why = (o.get("inconclusive_reason") or {}).get(c) or "not given"
                reasons[why] = reasons.get(why, 0) + 1
    return total, inconclusive, reasons, kinds


def lower_line(report):
    """The `lower` verdicts, counted by component and named by method and scene (slope of declared)."""
    count, named = 0, []
    for o in rp.orders(report):
        parts = []
        for c in rp.components(report):
            if rp.verdict(o, c) == "lower":
                declared = o.get("declared_rotation") if c == "rotation" else o.get("declared")
                parts.append(f"{c} {md.fmt((o.get('observed') or {}).get(c))} of {declared}")
        if parts:
            count += len(parts)
            named.append(f"{o['integrator']} on {o['scene']} ({', '.join(parts)})")
    if not named:
        return "- `lower` verdicts: none."
    return f"- `lower` verdicts: {count} components: " + "; ".join(named) + "."


def order_lines(report):
    total, inconclusive, reasons, kinds = _verdict_counts(report)
    if not total:
        return []
    why = ", ".join(f"{n} {r}" for r, n in sorted(reasons.items(), key=lambda x: (-x[1], x[0])))
    decided = ", ".join(f"{kinds[v]} {v}" for v in ("as declared", "lower", "exact") if kinds.get(v))
    lines = [f"- Orders: {total - inconclusive} of {total} component fits reach a verdict"
             + (f" ({decided})" if decided else "") + f"; {inconclusive} are "
             f"inconclusive" + (f" ({why})" if why else "") + ". \"exact\": every error of the ladder on the plateau, "
             "the largest step's too (no order to read, none contradicted); \"too few points\": under 4 in the window; "
             "\"floor\": as few because the runs reached the plateau (100 × the reference's error in that "
             "component or 10 × the rounding level); \"failed runs\": as few because the ladder's other runs "
             "failed, down to its finest step; "
             "\"wide interval\": 95 % half-width above 0.3; \"pre-asymptotic\": the halving "
             "slopes still move, or a slope below declared − 0.2 still climbs towards it at the smallest step, "
             "and the ladder's limits were reached; \"no asymptotic range above the plateau\": "
             "they still move where the plateau begins, and it does not certify; \"straddles\": the "
             "interval holds declared − 0.2, not certified by the plateau; "
             "\"self-convergence disagrees\": the method against itself reads another slope."]
    lines.append(lower_line(report))
    high = {}
    for o in rp.orders(report):
        if (o.get("declared") or 0) >= 8 and feeds_back(report, o["scene"]):
            decided = [c for c in rp.components(report) if rp.verdict(o, c) in ("as declared", "lower", "exact")]
            high.setdefault(o["integrator"], []).append(f"{o['scene']} {len(decided)}/{len(rp.components(report))}")
    if high:
        lines.append("- Order-8 methods where R feeds back (components with a verdict): "
                     + "; ".join(f"{n}: {', '.join(v)}" for n, v in high.items()) + ".")
    return lines


def exact_on(report, scene, name, metric):
    """True when every ok run of the method on the scene is below the reference's floor: exact there."""
    mine = [r for r in rp.by_integrator(rp.runs(report, scene)).get(name, []) if rp.ok(r)]
    return bool(mine) and all(rp.below_floor(r, metric) for r in mine)


def aggregate_cells(report, scene, metric, ratios_of_scene):
    """(cells, bounds, exact, variants) of one scene for the aggregates.

    cells: (lie, flat, target, ratio) of each Lie method once, against the
    cheapest of its geometry twins (pairs.against_twin: the same tableau, the
    suite's own code and the same controller; the smallest flat/Lie ratio);
    bounds: the cells whose ratio is a "≤"/"≥" bound (listed apart, never
    counted); exact: the Lie methods exact on the scene (left out);
    variants: {(flat, lie)} of the other flat methods (kept in the tables).
    """
    cells, bounds, exact, variants = [], [], [], set()
    runs = rp.runs(report, scene)
    by_lie = {}
    for flat, lie, _, ratios in ratios_of_scene:
        by_lie.setdefault(lie, []).append((flat, ratios))
    for lie, flats in by_lie.items():
        if exact_on(report, scene, lie, metric):
            exact.append(lie)
            continue
        for t in costs.TARGETS:
            ratios = {flat: ratios[t] for flat, ratios in flats}
            chosen = pairs.against_twin(runs, lie, ratios)
            if chosen is None:
                continue
            flat, ratio = chosen
            variants |= {(f, lie) for f, r in ratios.items() if f != flat and math.isfinite(r[0])}
            (bounds if ratio[4] else cells).append((lie, flat, t, ratio))
    return cells, bounds, exact, variants


def scene_line(scene, cells):
    """One R-feeds-back scene's answer: Lie cheaper or not, by how much, with the spread."""
    if not cells:
        return f"- {scene}: no pair reached a target with a measured (not bounded) ratio."
    values = sorted(r[0] for *_, r in cells)
    cheaper = sum(1 for v in values if v > 1)
    low, high = min(r[1] for *_, r in cells), max(r[2] for *_, r in cells)
    lie_wins = cheaper * 2 > len(values)
    who = "the Lie method is cheaper" if lie_wins else "**the flat method wins**"
    count = cheaper if lie_wins else len(values) - cheaper  # the count of the side named
    return (f"- {scene}: {who} in {count} of {len(values)} pair × target cells; flat/Lie {values[0]:.2f} to "
            f"{values[-1]:.2f} (median {values[len(values) // 2]:.2f}; repeats span {low:.2f}–{high:.2f}).")


def answer_lines(answers, metric=rp.DEFAULT_METRIC):
    """The first screen's answer: does keeping R on SO(3) pay, where, and by how much ([(scene, cells)])."""
    return answer.lines(answers, metric)


def scene_answers(report, metric=rp.DEFAULT_METRIC):
    """[(scene, cells)] per scene where R feeds back, read as the findings read them (error_max)."""
    with rp.errors_read("max"):
        return [(scene, aggregate_cells(report, scene, metric, pair_ratios(report, scene, metric))[0])
                for scene in rp.scenes(report) if rp.runs(report, scene) and feeds_back(report, scene)]


def frontier_lines(report, scenes, metric):
    """Per scene where R feeds back and target: the best Lie method over the best library method (frontier.py)."""
    cells = [(scene, target, frontier.frontier(report, scene, metric, target))
             for scene in scenes if feeds_back(report, scene) for target in costs.TARGETS]
    cells = [(scene, target, f) for scene, target, f in cells if f is not None]
    if not cells:
        return []
    text = "; ".join(f"{scene} at {target:.0e}: {lie} / {library} {ratio_text(ratio)}"
                     for scene, target, (lie, library, ratio) in cells)
    families = ", ".join(pairs.LIBRARY_FAMILIES)
    return [f"- The Lie frontier where R feeds back (the best Lie method's time over the best library method's, "
            f"families {families}; below 1 the Lie method is cheaper; the goal is ≤ {frontier.GOAL}): {text}."]


def findings_section(report, metric=rp.DEFAULT_METRIC, figure=()):
    """The findings read the worst error over the run (error_max), whatever the tables read.

    figure: lines put right after the answer when it has a measured ratio
    (summary.md's answer.png), before any definition.
    """
    with rp.errors_read("max"):
        return _findings_section(report, metric, list(figure))


def _findings_section(report, metric=rp.DEFAULT_METRIC, figure=()):
    lines = [HEADING, ""]
    scenes = [s for s in rp.scenes(report) if rp.runs(report, s)]
    if not scenes:
        return lines + ["No runs: nothing to find.", ""]
    targets = ", ".join(f"{t:.0e}" for t in costs.TARGETS)
    lines += [f"Which method is cheapest at a {metric} error of {targets}, and whether keeping R on SO(3) pays: "
              f"wall time to reach the target {costs.HOW}. A pair shares its Butcher tableau (the methods' "
              "`tableau`); its ratio is flat time / Lie time (above 1: the Lie method is cheaper), the median "
              "over the timed repeats with [lowest–highest] (repeat k reads every run's k-th timed sample); "
              "\"≤\"/\"≥\": a side's cheapest run is already there, so the ratio is a bound. Accuracy here is the "
              "worst error over the run (every output time, `error_max`), not the error at t_end. The counts "
              "and ranges take each Lie method once, against the cheapest flat method with its tableau that differs "
              "from it only in the geometry (the suite's own code, the same controller; a library's method with the "
              "same tableau is a variant); bounds "
              "and scenes where the Lie method is exact (every run at the reference floor) are listed apart.", ""]
    summary, rows, pair_rows, unreached = [], [], [], 0
    bounded, exact_lines, per_scene, answers = [], [], [], []
    for scene in scenes:
        kind = scene_kind(report, scene)
        table = costs.cost_rows(report, scene, metric)
        rows.append([scene, kind] + [_cheapest_cell(table, t) for t in costs.TARGETS])
        scene_ratios = pair_ratios(report, scene, metric)
        cells, bounds, exact, variants = aggregate_cells(report, scene, metric, scene_ratios)
        summary += [(feeds_back(report, scene), r[0]) for *_, r in cells]
        bounded += [f"{scene} {flat} / {lie} at {t:.0e}: {ratio_text(r)}" for lie, flat, t, r in bounds]
        exact_lines += [f"{lie} on {scene}" for lie in exact]
        if feeds_back(report, scene):
            per_scene.append(scene_line(scene, cells))
            answers.append((scene, cells))
        for flat, lie, tableau, ratios in scene_ratios:
            if not any(math.isfinite(ratios[t][0]) for t in costs.TARGETS):
                unreached += 1  # neither target reached by both: nothing to compare here
                continue
            pair_rows.append([scene, "R feeds back" if feeds_back(report, scene) else kind.split(" (")[0],
                              f"{flat} / {lie}" + (" (variant)" if (flat, lie) in variants else ""), tableau]
                             + [ratio_text(ratios[t]) for t in costs.TARGETS])
    for where, label in ((True, "where R feeds back"), (False, "on homogeneous scenes")):
        values = sorted(m for w, m in summary if w == where)
        if values:
            cheaper = sum(1 for v in values if v > 1)
            lines.append(f"- Keeping R on SO(3) {label}: the Lie method is cheaper in {cheaper} of {len(values)} "
                         f"pair × target cells; flat/Lie time ratio {values[0]:.2f} to {values[-1]:.2f} "
                         f"(median {values[len(values) // 2]:.2f}).")
    if not summary:
        lines.append("- No same-tableau flat/Lie pair reached a target in this report.")
    if per_scene:
        lines += ["- Per scene where R feeds back:"] + ["  " + line for line in per_scene]
    if exact_lines:
        lines.append("- Exact (every run at the reference floor; left out of the counts): "
                     + ", ".join(exact_lines) + ".")
    if bounded:
        lines.append(f"- Bounds, not counted ({len(bounded)}): " + "; ".join(bounded) + ".")
    lines[2:2] = answer_lines(answers, metric) + (list(figure) if answer.measured(answers) else [])
    lines += frontier_lines(report, scenes, metric)
    lines += regime.findings_lines(report, metric) + order_lines(report) + horizon.finding_lines(report)
    lines += horizon_ladder.finding_lines(report)
    lines += reversibility.finding_lines(report) + stability.finding_lines(report) + [""]
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

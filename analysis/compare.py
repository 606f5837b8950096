#!/usr/bin/python3
"""Compare two rollbench reports run by run.

    analysis/compare.py A.json B.json [--out FILE.md] [--all]

For each (scene, integrator, step size or tolerance) in both reports: the
change in status, error, drift and wall time, and per (scene, integrator)
the change in observed order. Time counts as changed only when a
Mann–Whitney U test (SciPy) over the raw samples gives p < 0.01 and the medians
differ by more than 5 %, so that timing noise is not reported as change;
with too few timed repeats for that test to reach p < 0.01 at all (its
smallest p with n and m samples is 2 / C(n + m, n): 5 against 5 are
needed), it says that no timing change can be detected, not "No change".
Per integrator, a pooled test over all its runs in both reports: the
log ratio of each run's median times, log(B / A), tested by a Wilcoxon
signed-rank test (SciPy, two-sided) against zero; the integrator's time
counts as changed when p < 0.01 over at least 8 runs (the fewest for
which that test can reach 0.01: its smallest p is 2 / 2^n) and the median ratio differs from 1 by
more than 5 %. So a uniform slowdown of one method is found at 3 repeats,
where no single run's test can see it.
Reports whose runs are not the same measurement are refused (exit 2),
naming both values: their runs are of other scenes, no run is in both, or
a scene's end time, the output grid (dt_out) or the error grid (error_dt)
differ. A different step or tolerance ladder is stated (runs only in one
report), not refused. A report that does not read (analysis/report.py's
checks: a key of the wrong type or range, a scene name that is not a
file name, JSON nested deeper than 64 levels, not UTF-8, over 1 GiB, not a
regular file) is refused the same way, naming the file and the key.
Errors and drift are deterministic: a relative change over 5 % counts,
except between values that both sit at rounding level. Prints a table of
the changes (every row with --all); exit status 0 (2 for an unreadable
report or two reports that do not measure the same runs).
"""
import argparse
import math
import os
import sys

import numpy as np
from scipy import stats

if __package__ in (None, ""):
    sys.path[0] = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

from analysis import report as rp  # noqa: E402
from analysis import safe_files  # noqa: E402

ALPHA = 0.01
TIME_RATIO = 0.05   # median change that matters
VALUE_RATIO = 0.05  # error and drift change that matters
ORDER_DELTA = 0.1   # observed order change that matters
# below this, errors and drift are rounding noise: 1e-15 against 3e-15 is no change
ROUNDING = {"error": 1e-13, "energy": 1e-12, "rotation_defect": 1e-13}


def run_key(run):
    """(scene, integrator, setting text); the text carries h or the tolerances to 12 digits."""
    return (run.scene, run.integrator, rp.setting(run, digits=12))


def _value_change(a, b, threshold_ratio, rounding):
    """None when equal enough, else a short text a → b."""
    fa, fb = math.isfinite(a), math.isfinite(b)
    if not fa and not fb:
        return None
    if fa != fb:
        return f"{_fmt(a)} → {_fmt(b)}"
    if abs(a) <= rounding and abs(b) <= rounding:
        return None
    scale = max(abs(a), abs(b))
    if abs(a - b) <= threshold_ratio * scale:
        return None
    return f"{_fmt(a)} → {_fmt(b)} (×{b / a:.3g})" if a else f"{_fmt(a)} → {_fmt(b)}"


def _fmt(v):
    return f"{v:.3g}" if math.isfinite(v) else "—"


def _error_value(run, component):
    # below the reference's floor is "as good as measurable", not "missing"
    if rp.below_floor(run, component):
        return 0.0
    return rp.error(run, component)


def smallest_p(n, m):
    """The smallest two-sided p an exact Mann–Whitney test can give with n and m samples: 2 / C(n + m, n)."""
    if n < 1 or m < 1:
        return 1.0
    return min(1.0, 2.0 / math.comb(n + m, n))


def detectable(a, b):
    """Whether the two runs' timed repeats are enough for a time change to pass p < ALPHA at all."""
    return smallest_p(rp.samples(a).size, rp.samples(b).size) < ALPHA


def time_change(a, b):
    """(ratio of medians B / A, p, changed) from the raw samples."""
    sa, sb = rp.samples(a), rp.samples(b)
    if sa.size == 0 or sb.size == 0:
        ma, mb = rp.wall(a), rp.wall(b)
        return (mb / ma if ma > 0 else math.nan), math.nan, False
    ma, mb = float(np.median(sa)), float(np.median(sb))
    ratio = mb / ma if ma > 0 else math.nan
    # exact distribution for small samples without ties, else the normal approximation
    p = float(stats.mannwhitneyu(sa, sb, alternative="two-sided", method="auto").pvalue)
    if not math.isfinite(p):
        p = 1.0  # every sample equal: nothing to conclude
    changed = p < ALPHA and math.isfinite(ratio) and abs(ratio - 1.0) > TIME_RATIO
    return ratio, p, changed


# a two-sided signed-rank test on n values has smallest p 2 / 2^n: 8 runs are the fewest that can reach 0.01
POOLED_MIN_RUNS = 8


def pooled_time_changes(rows):
    """Per integrator over its runs in both reports: {integrator: {"runs", "ratio", "p", "changed"}}.

    The values tested are log(median B / median A) per run; "ratio" is exp of their median."""
    by_method = {}
    for row in rows:
        ma, mb = row["time"]
        if not (math.isfinite(ma) and math.isfinite(mb)) or ma <= 0 or mb <= 0:
            continue
        q = mb / ma  # of two extreme times (a hostile report's) it leaves the double's range: a difference of logs
        by_method.setdefault(row["key"][1], []).append(math.log(q) if 0 < q < math.inf else math.log(mb) - math.log(ma))
    out = {}
    for name, logs in by_method.items():
        logs = np.array(logs)
        with np.errstate(over="ignore"):
            ratio = float(np.exp(np.median(logs)))
        if logs.size < POOLED_MIN_RUNS or not np.any(logs != 0.0):
            p = 1.0  # too few runs to conclude, or every ratio exactly 1
        else:
            p = float(stats.wilcoxon(logs, alternative="two-sided").pvalue)
        changed = p < ALPHA and abs(ratio - 1.0) > TIME_RATIO
        out[name] = {"runs": int(logs.size), "ratio": ratio, "p": p, "changed": changed}
    return out


def compare_runs(a, b, metrics=(rp.DEFAULT_METRIC,)):
    """One row: the values side by side and the list of changes (kind, text) in the metrics given."""
    changes = []
    if a.status != b.status:
        changes.append(("status", f"{a.status} → {b.status}"))
    for c in metrics:
        text = _value_change(_error_value(a, c), _error_value(b, c), VALUE_RATIO, ROUNDING["error"])
        if text:
            changes.append((f"error.{c}", text))
    for key in ("energy", "rotation_defect"):
        va = rp.num((a.entry.get("drift") or {}).get(key))
        vb = rp.num((b.entry.get("drift") or {}).get(key))
        text = _value_change(va, vb, VALUE_RATIO, ROUNDING[key])
        if text:
            changes.append((f"drift.{key}", text))
    ratio, p, changed = time_change(a, b)
    if changed:
        changes.append(("time", f"×{ratio:.3g} {'slower' if ratio > 1 else 'faster'} (p = {p:.2g})"))
    return {"key": run_key(a), "status": (a.status, b.status),
            "worst": (rp.error(a, "worst"), rp.error(b, "worst")),
            "energy": (rp.num((a.entry.get("drift") or {}).get("energy")),
                       rp.num((b.entry.get("drift") or {}).get("energy"))),
            "time": (rp.wall(a), rp.wall(b)), "ratio": ratio, "p": p, "changes": changes,
            "detectable": detectable(a, b), "repeats": (rp.samples(a).size, rp.samples(b).size)}


def compare_orders(a, b):
    """Per scene × method in both: the observed orders that moved, in every error component either report lists."""
    rows = []
    ob = {(o["scene"], o["integrator"]): o for o in rp.orders(b)}
    components = rp.unique(rp.components(a) + rp.components(b))
    for o in rp.orders(a):
        key = (o["scene"], o["integrator"])
        if key not in ob:
            continue
        changes = []
        for c in components:
            va, vb = rp.observed(o, c), rp.observed(ob[key], c)
            if math.isfinite(va) != math.isfinite(vb) or (math.isfinite(va) and abs(va - vb) > ORDER_DELTA):
                changes.append((f"order.{c}", f"{_fmt(va)} → {_fmt(vb)}"))
        rows.append({"key": key, "changes": changes})
    return rows


class Mismatch(Exception):
    """The two reports do not measure the same runs."""


def _grid(report, key):
    value = rp.num((report.get("options") or {}).get(key))
    return value if math.isfinite(value) else None


def _end_times(report):
    """{scene: t_end} from the references (every run of a scene ends there), else the runs' own."""
    out = {}
    for ref in report.get("references") or []:
        t = rp.num(ref.get("t_end"))
        if math.isfinite(t):
            out[ref["scene"]] = t
    for run in rp.runs(report):
        t = rp.num(run.entry.get("t_end"))
        if run.scene not in out and math.isfinite(t):
            out[run.scene] = t
    return out


def _names(names, shown=5):
    names = sorted(names)
    return ", ".join(names[:shown]) + (f" and {len(names) - shown} more" if len(names) > shown else "")


def check_comparable(a, b, name_a="A", name_b="B"):
    """Raise Mismatch naming both values when the scenes, a scene's end time or the output or error grid differ,
    or when no run is in both reports."""
    problems = []
    sa, sb = {r.scene for r in rp.runs(a)}, {r.scene for r in rp.runs(b)}
    if sa != sb:
        only = [f"only in {name}: {_names(s)}" for name, s in ((name_a, sa - sb), (name_b, sb - sa)) if s]
        problems.append(f"their runs are of other scenes ({'; '.join(only)})")
    elif not {run_key(r) for r in rp.runs(a)} & {run_key(r) for r in rp.runs(b)}:
        problems.append("no run (scene, integrator and step or tolerance) is in both")
    ta, tb = _end_times(a), _end_times(b)
    for scene in ta:
        if scene in tb and ta[scene] != tb[scene]:
            problems.append(f"scene '{scene}' ends at t = {ta[scene]:.12g} in {name_a} but at "
                            f"t = {tb[scene]:.12g} in {name_b}")
    for key, what in (("dt_out", "output grid dt_out"), ("error_dt", "error grid error_dt")):
        ga, gb = _grid(a, key), _grid(b, key)
        if ga != gb:
            problems.append(f"the {what} is {_fmt_grid(ga)} in {name_a} but {_fmt_grid(gb)} in {name_b}")
    if problems:
        raise Mismatch("the reports do not measure the same runs: " + "; ".join(problems))


def _fmt_grid(value):
    return "none" if value is None else f"{value:.12g}"


def ladder_note(a, b, name_a="A", name_b="B"):
    """A sentence when the step or tolerance ladders differ, else None."""
    notes = []
    for key, what in (("h", "step ladder"), ("tol", "tolerance ladder")):
        la = [rp.num(x) for x in (a.get("options") or {}).get(key) or []]
        lb = [rp.num(x) for x in (b.get("options") or {}).get(key) or []]
        if la != lb:
            notes.append(f"the {what} differs ({len(la)} values in {name_a}, {len(lb)} in {name_b})")
    if not notes:
        return None
    return "Note: " + "; ".join(notes) + ": only the runs in both are compared (listed below)."


def compare_reports(a, b):
    """{"runs": rows, "orders": rows, "pooled": {integrator: test}, "only_a": keys, "only_b": keys,
    "changes": [(key, kind, text)]}; a pooled change's key is ("all scenes", integrator, "N runs")."""
    runs_b = {run_key(r): r for r in rp.runs(b)}
    keys_a = [run_key(r) for r in rp.runs(a)]
    metrics = rp.unique(rp.metrics(a) + rp.metrics(b))
    rows = [compare_runs(r, runs_b[run_key(r)], metrics) for r in rp.runs(a) if run_key(r) in runs_b]
    orders = compare_orders(a, b)
    changes = [(row["key"], kind, text) for row in rows + orders for kind, text in row["changes"]]
    pooled = pooled_time_changes(rows)
    for name, t in pooled.items():
        if t["changed"]:
            changes.append((("all scenes", name, f"{t['runs']} runs"), "time (pooled)",
                            f"×{t['ratio']:.3g} {'slower' if t['ratio'] > 1 else 'faster'} "
                            f"(median over its runs, signed-rank p = {t['p']:.2g})"))
    return {"runs": rows, "orders": orders, "changes": changes, "pooled": pooled,
            "only_a": [k for k in keys_a if k not in runs_b],
            "only_b": [k for k in runs_b if k not in set(keys_a)]}


def _table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c).replace("|", "\\|") for c in row) + " |" for row in rows]
    return out


def format_markdown(result, name_a="A", name_b="B", every_row=False):
    lines = [f"# rollbench: {name_b} against {name_a}", "",
             f"{len(result['runs'])} runs in both; time changes need p < {ALPHA} (Mann–Whitney U over the "
             f"raw samples) and a median change over {TIME_RATIO:.0%}; error and drift changes over "
             f"{VALUE_RATIO:.0%}; order changes over {ORDER_DELTA}.", ""]
    changes = result["changes"]
    if result.get("note"):
        lines += [result["note"], ""]
    pooled = result.get("pooled") or {}
    if pooled:
        lines += [f"Timing, pooled: per integrator, a Wilcoxon signed-rank test of log(median {name_b} / median "
                  f"{name_a}) over its runs ({len(pooled)} tests, at least {POOLED_MIN_RUNS} runs each); a change "
                  f"needs p < {ALPHA} and a median ratio over {TIME_RATIO:.0%} from 1.", ""]
    blind = [r for r in result["runs"] if not r.get("detectable", True)]
    if blind:
        fewest = min(min(r["repeats"]) for r in blind)
        lines += [f"Timing: {len(blind)} of {len(result['runs'])} runs have too few timed repeats (as few as "
                  f"{fewest}) for a Mann–Whitney test to reach p < {ALPHA} (with n and m samples its smallest p is "
                  f"2 / C(n + m, n): 5 against 5 are needed): no timing change can be detected for them; run "
                  "both sweeps with more --repeats.", ""]
    tested = sum(1 for r in result["runs"] if math.isfinite(r["p"]) and r.get("detectable", True))
    if tested:
        # many tests at once: a few "changes" can be chance (or a machine whose load changed between runs)
        lines += [f"Timing: {tested} rank tests; at p < {ALPHA} about {tested * ALPHA:.1f} would pass by chance "
                  "alone, before the 5 % filter.", ""]
    if changes:
        lines += [f"## {len(changes)} changes", ""]
        lines += _table(["scene", "integrator", "setting", "what", "change"],
                        [[*key, ""][:3] + [kind, text] for key, kind, text in changes])
    else:
        pooled_ok = [n for n, t in pooled.items() if t["runs"] >= POOLED_MIN_RUNS]
        if blind and pooled_ok:
            lines += [f"No change in status, error, drift or order, nor in time: no single run has repeats enough "
                      f"for its own test ({len(blind)} above), and the pooled test finds no change in "
                      f"{len(pooled_ok)} integrators with {POOLED_MIN_RUNS} runs or more."]
        elif blind and len(blind) == len(result["runs"]):
            lines += ["No change in status, error, drift or order; no timing change can be detected (too few "
                      "timed repeats, above)."]
        elif blind:
            lines += ["No change in status, error, drift or order, nor in time where it can be detected (the runs "
                      "above excepted)."]
        else:
            lines += ["No change: no significant difference in status, error, drift, order or time."]
    lines.append("")
    for label, keys in (("only in " + name_a, result["only_a"]), ("only in " + name_b, result["only_b"])):
        if keys:
            lines += [f"## Runs {label}: {len(keys)}", ""] + [f"- {' / '.join(k)}" for k in keys] + [""]
    if every_row:
        rows = []
        for r in result["runs"]:
            rows.append([*r["key"], " → ".join(str(s) for s in r["status"]),
                         " → ".join(_fmt(v) for v in r["worst"]), " → ".join(_fmt(v) for v in r["energy"]),
                         " → ".join(_fmt(v) for v in r["time"]), _fmt(r["ratio"]), _fmt(r["p"]),
                         "; ".join(kind for kind, _ in r["changes"]) or "—"])
        lines += ["## Every run", ""]
        lines += _table(["scene", "integrator", "setting", "status", "worst error", "energy drift",
                         "time (s)", "time ratio", "p", "changed"], rows)
        lines.append("")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("a", help="the baseline report")
    parser.add_argument("b", help="the report compared with it")
    parser.add_argument("--out", help="also write the table to this Markdown file")
    parser.add_argument("--all", action="store_true", help="list every run, not only the changes")
    args = parser.parse_args(argv)
    out = None
    try:
        # the output's folder opened and the target checked first, under the path rule (analysis/safe_files.py)
        out = safe_files.OutputFile(args.out) if args.out else None
        a, b = rp.load(args.a), rp.load(args.b)
        check_comparable(a, b, args.a, args.b)
        result = compare_reports(a, b)
        result["note"] = ladder_note(a, b, args.a, args.b)
        text = format_markdown(result, args.a, args.b, args.all)
        print(text)
        if out:
            out.write(text)
    except (rp.ReportError, Mismatch, safe_files.OutputFileError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    finally:
        if out:
            out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())

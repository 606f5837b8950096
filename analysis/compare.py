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
Errors and drift are deterministic: a relative change over 5 % counts,
except between values that both sit at rounding level. Prints a table of
the changes (every row with --all); exit status 0 (2 for an unreadable report).
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

ALPHA = 0.01
TIME_RATIO = 0.05   # median change that matters
VALUE_RATIO = 0.05  # error and drift change that matters
ORDER_DELTA = 0.1   # observed order change that matters
# below this, errors and drift are rounding noise: 1e-15 against 3e-15 is no change
ROUNDING = {"error": 1e-13, "energy": 1e-12, "rotation_defect": 1e-13}


def run_key(run):
    """(scene, integrator, setting text); the text carries h or the tolerances to 12 digits."""
    return (run["scene"], run["integrator"], rp.setting(run, digits=12))


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


def compare_runs(a, b, metrics=(rp.DEFAULT_METRIC,)):
    """One row: the values side by side and the list of changes (kind, text) in the metrics given."""
    changes = []
    if a.get("status") != b.get("status"):
        changes.append(("status", f"{a.get('status')} → {b.get('status')}"))
    for c in metrics:
        text = _value_change(_error_value(a, c), _error_value(b, c), VALUE_RATIO, ROUNDING["error"])
        if text:
            changes.append((f"error.{c}", text))
    for key in ("energy", "rotation_defect"):
        va = rp.num((a.get("drift") or {}).get(key))
        vb = rp.num((b.get("drift") or {}).get(key))
        text = _value_change(va, vb, VALUE_RATIO, ROUNDING[key])
        if text:
            changes.append((f"drift.{key}", text))
    ratio, p, changed = time_change(a, b)
    if changed:
        changes.append(("time", f"×{ratio:.3g} {'slower' if ratio > 1 else 'faster'} (p = {p:.2g})"))
    return {"key": run_key(a), "status": (a.get("status"), b.get("status")),
            "worst": (rp.error(a, "worst"), rp.error(b, "worst")),
            "energy": (rp.num((a.get("drift") or {}).get("energy")), rp.num((b.get("drift") or {}).get("energy"))),
            "time": (rp.wall(a), rp.wall(b)), "ratio": ratio, "p": p, "changes": changes,
            "detectable": detectable(a, b), "repeats": (rp.samples(a).size, rp.samples(b).size)}


def compare_orders(a, b):
    rows = []
    ob = {(o["scene"], o["integrator"]): o for o in rp.orders(b)}
    for o in rp.orders(a):
        key = (o["scene"], o["integrator"])
        if key not in ob:
            continue
        changes = []
        for c in ("contact", "rotation"):
            va, vb = rp.observed(o, c), rp.observed(ob[key], c)
            if math.isfinite(va) != math.isfinite(vb) or (math.isfinite(va) and abs(va - vb) > ORDER_DELTA):
                changes.append((f"order.{c}", f"{_fmt(va)} → {_fmt(vb)}"))
        rows.append({"key": key, "changes": changes})
    return rows


def compare_reports(a, b):
    """{"runs": rows, "orders": rows, "only_a": keys, "only_b": keys, "changes": [(key, kind, text)]}."""
    runs_b = {run_key(r): r for r in rp.runs(b)}
    keys_a = [run_key(r) for r in rp.runs(a)]
    metrics = rp.unique(rp.metrics(a) + rp.metrics(b))
    rows = [compare_runs(r, runs_b[run_key(r)], metrics) for r in rp.runs(a) if run_key(r) in runs_b]
    orders = compare_orders(a, b)
    changes = [(row["key"], kind, text) for row in rows + orders for kind, text in row["changes"]]
    return {"runs": rows, "orders": orders, "changes": changes,
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
        if blind and len(blind) == len(result["runs"]):
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
    try:
        a, b = rp.load(args.a), rp.load(args.b)
    except rp.ReportError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    text = format_markdown(compare_reports(a, b), args.a, args.b, args.all)
    print(text)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The stability study's two limits per scene and fixed-step method (docs/usage.md, "Stability";
bench/lib/stability.hpp), as the report's `stability.largest_stable_h` entries carry them:

- the blow-up step (`blow_up.at[]`, one per horizon): the smallest step whose run stops or passes a blow-up bound by
  T, before it drifts out of its bounds or within `thresholds.blow_up_steps` steps of it (the step's own exponential
  growth); `blow_up.same_at_every_horizon` says whether it moved;
- the drift-limited step h*(T) (`drift_limited[]`, one per horizon): the largest step whose run to T keeps every
  drift bound, with what ended the next step (`limited_by`: energy, rotation-defect or blow-up) and its value.

A report written before the two limits (no `drift_limited`) has one "largest stable step" per entry at one horizon;
limits() answers None for it and the summary and figure fall back to that."""
import math

from analysis import markdown as md
from analysis import report as rp

QUANTITY_TEXT = {"energy": "energy", "rotation-defect": "rotation defect", "blow-up": "blow-up"}


def limits(entry):
    """(blow_up, drift_limited) of an entry: [{horizon, h, cause, status, smallest_tried}], [{horizon, h,
    at_limit, next_h, limited_by, blow_up, value, bound}], each by horizon; None for a report of before."""
    drift = entry.get("drift_limited")
    if not isinstance(drift, list) or not drift:
        return None
    blow = (entry.get("blow_up") or {}).get("at") or []
    return [b for b in blow if isinstance(b, dict)], [d for d in drift if isinstance(d, dict)]


def has_limits(entries):
    return any(limits(e) is not None for e in entries)


def horizons(entries):
    """Every horizon (s) of the entries' drift-limited steps, increasing."""
    out = set()
    for e in entries:
        got = limits(e)
        for d in (got[1] if got else []):
            if math.isfinite(rp.num(d.get("horizon"))):
                out.add(rp.num(d.get("horizon")))
    return sorted(out)


def seconds(t):
    return f"{t:g} s"


def blow_up_same(entry):
    """Whether the blow-up step is the same at every horizon (the report's flag, else read from the steps)."""
    flag = (entry.get("blow_up") or {}).get("same_at_every_horizon")
    if isinstance(flag, bool):
        return flag
    got = limits(entry)
    steps = {rp.num(b.get("h")) for b in (got[0] if got else [])}
    return len({("nan" if math.isnan(h) else h) for h in steps}) <= 1


def blow_up_text(entry):
    """The blow-up step: '0.5 (chart-limit)' where the same at every horizon, else '0.5 at 10 s, 0.25 at 1000 s';
    '> 8' where no step tried blew up (the ladder's top), '≤ 0.000977' where every step tried did."""
    got = limits(entry)
    if not got or not got[0]:
        return "—"

    def one(b):
        h = rp.num(b.get("h"))
        if math.isnan(h):
            return f"> {md.fmt(_top(entry))}"
        cause = b.get("cause")
        if cause == "stopped" and b.get("status"):
            cause = b["status"]
        return ("≤ " if b.get("smallest_tried") else "") + md.fmt(h) + (f" ({cause})" if cause else "")

    if blow_up_same(entry):
        return one(got[0][0])
    return ", ".join(f"{one(b)} at {seconds(rp.num(b.get('horizon')))}" for b in got[0])


def _top(entry):
    tried = [h for h in rp.tested_h(entry) if math.isfinite(h)]
    return max(tried) if tried else math.nan


def drift_text(d):
    """One drift-limited step: '0.0625 (rotation defect 0.71 > 0.5 at 0.125)', 'none (...)', '≥ 8'."""
    h = rp.num(d.get("h"))
    if d.get("at_limit"):
        return f"≥ {md.fmt(h)}"
    step = md.fmt(h) if math.isfinite(h) else "none"
    what = d.get("limited_by")
    if not what:
        return step
    at = f"at {md.fmt(rp.num(d.get('next_h')))}"
    if what == "blow-up":
        how = d.get("blow_up") or "stopped"
        if how == "stopped" and d.get("status"):
            how = d["status"]
        return f"{step} (blow-up {at}: {how})"
    value, bound = rp.num(d.get("value")), rp.num(d.get("bound"))
    return f"{step} ({QUANTITY_TEXT.get(what, what)} {past(value, bound)} > {md.fmt(bound)} {at})"


def past(value, bound):
    """A value past its bound, with the digits that show it past (0.1004 against 0.1: '0.1004')."""
    for digits in (3, 4, 6, 9):
        text = f"{value:.{digits}g}" if math.isfinite(value) else md.fmt(value)
        if not math.isfinite(value) or not math.isfinite(bound) or float(text) > bound:
            return text
    return text


def drift_at(entry, horizon):
    got = limits(entry)
    for d in (got[1] if got else []):
        if rp.num(d.get("horizon")) == horizon:
            return d
    return None


def short_limits(entry, times):
    """'blow-up 0.5; h*(10 s) 0.0625, h*(100 s) 0.0313, h*(1000 s) 0.0156 limited by rotation defect' (the
    quantity once where every horizon names the same)."""
    parts, quantities = [], []
    for t in times:
        d = drift_at(entry, t)
        if d is None:
            continue
        h = rp.num(d.get("h"))
        parts.append(f"h*({seconds(t)}) " + (f"≥ {md.fmt(h)}" if d.get("at_limit") else
                                             md.fmt(h) if math.isfinite(h) else "none"))
        quantities.append(QUANTITY_TEXT.get(d.get("limited_by"), d.get("limited_by")) if d.get("limited_by") else None)
    named = [q for q in quantities if q]
    if named and len(set(named)) == 1:
        text = ", ".join(parts) + f" limited by {named[0]}"
    else:
        text = ", ".join(p + (f" ({q})" if q else "") for p, q in zip(parts, quantities))
    return f"blow-up step {blow_up_text(entry)}; {text}"


def finding_lines(report):
    """Per stability scene, each method's blow-up step and h*(T) per horizon (methods with the same limits named
    together), then where the blow-up step moved with the horizon."""
    entries = [e for e in rp.stable_steps(report) if limits(e) is not None]
    if not entries:
        return []
    times = horizons(entries)
    bounds = entries[0].get("thresholds") or {}
    lines = []
    steps = md.fmt(rp.num(bounds.get("blow_up_steps")))
    for scene in rp.unique(e["scene"] for e in entries):
        groups = {}
        for e in (e for e in entries if e["scene"] == scene):
            groups.setdefault(short_limits(e, times), []).append(e["integrator"])
        text = "; ".join(f"{' = '.join(names)}: {limits_text}" for limits_text, names in groups.items())
        lines.append(f"- Stability on {scene} (the blow-up step: the smallest step whose run stops or passes a "
                     f"blow-up bound before it drifts out of its bounds or within {steps} steps of it; h*(T): the "
                     "largest step whose run to T keeps the energy error within "
                     f"{md.fmt(rp.num(bounds.get('energy')))} of the scale and ‖RᵀR − I‖_F within "
                     f"{md.fmt(rp.num(bounds.get('rotation_defect')))}, limited by what the next step crossed): "
                     + text + ".")
    moved = [e for e in entries if not blow_up_same(e)]
    same = len(entries) - len(moved)
    horizon_list = ", ".join(seconds(t) for t in times)
    line = (f"- The blow-up step is the same at every horizon ({horizon_list}) for {same} of {len(entries)} "
            "method × scene")
    if moved:
        line += ("; it moves for " + "; ".join(f"{e['integrator']} on {e['scene']} ({blow_up_text(e)})"
                                               for e in moved)
                 + " (a step that fails only late, with no drift before: a Newton iteration or the exponential "
                 "chart failing at a state the run reaches only then)")
    return lines + [line + "."]

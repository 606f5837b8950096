"""The reversibility defect of the fixed-step runs (docs/model.md#time-reversal, a run's `reversibility` in
docs/formats.md): the findings' line per scene, which methods come back to the start at rounding at every step
they took and how far the others miss."""
import math

from analysis import markdown as md
from analysis import report as rp

# A defect at most this, at every step a method took, is rounding (the symmetric methods read 1e-15 .. 1e-12;
# an explicit method of order 4 at h = 0.02 misses by 1e-8 and more).
AT_ROUNDING = 1e-10


def largest_defects(report, scene):
    """{integrator: (largest worst defect over its runs with a measured defect, h there)}, in run order."""
    largest = {}
    for r in rp.runs(report, scene, adaptive=False):
        d = r.entry.get("reversibility") or {}
        worst = rp.num(d.get("worst"))
        if d.get("status") != "ok" or not math.isfinite(worst):
            continue
        name = r.integrator
        if name not in largest or worst > largest[name][0]:
            largest[name] = (worst, r.h)
    return largest


def finding_lines(report):
    """One line per scene with measured defects: the methods at rounding, then each other method's largest
    defect with its step."""
    lines = []
    for scene in rp.scenes(report):
        largest = largest_defects(report, scene)
        if not largest:
            continue
        symmetric = [n for n, (w, _) in largest.items() if w <= AT_ROUNDING]
        missed = sorted(((w, h, n) for n, (w, h) in largest.items() if w > AT_ROUNDING), reverse=True)
        parts = []
        if symmetric:
            parts.append(f"back at the start to rounding (≤ {AT_ROUNDING:.0e}) at every step for "
                         + ", ".join(symmetric))
        if missed:
            parts.append("missed by " + ", ".join(f"{n} {md.fmt(w)} (h = {md.fmt(h)})" for w, h, n in missed))
        lines.append(f"- Reversibility on {scene} (v → −v, run back, v → −v; the largest defect over each "
                     f"fixed-step method's runs): " + "; ".join(parts) + ".")
    return lines

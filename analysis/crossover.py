"""The regime map's border: where the flat/Lie time ratio crosses 1.

The predictor is the ball's rotation rate over the bowl's frequency at the
start, X = |ω0| / Ω (the report's `omega0` and `bowl_frequency`, Ω² = g κ /
((1 − r κ)(1 + Ī / (m r²))), κ the largest principal curvature at the start
contact; X = ∞ on a plane). Why: a flat method integrates R' = ω̂ R as a
polynomial in h, so its error grows with |ω| h; a Lie method moves R by
exp(h ω̂) exactly while ω is constant, so its error grows with how fast ω
changes, on the motion's time scale 1 / Ω. Where the ball turns slowly next
to the bowl's period (X small) both need the step the bowl sets, and the Lie
method's extra work per step (exp, dexp⁻¹) makes it the dearer one.

The rules, each a function tested on synthetic reports
(tests/analysis/test_crossover.py):

- outcome: a cell's winner from its ratio: a tie where the timed repeats'
  [lowest–highest] holds 1 (the difference is within the timing's noise);
  no outcome for a ratio that is only a bound (a side's cheapest run already
  past the target: not a measurement).
- fit: a logistic fit of "the Lie side wins" on log10 X over the decided
  cells × targets where R feeds back (ties left out); the crossover x* where
  it is 1/2, the point where flat/Lie crosses 1 as the grid sees it, with a
  95 % percentile interval from resampling the cells (their targets
  together). Not a straight line through log10(flat/Lie): the ratio
  saturates at about 1.5 where X is large, and such a line, tried first, is
  pulled by the saturated cells that say nothing about where the winner
  changes.
- held-out check: each held-out scene's predicted winner (Lie where X > x*)
  against its measured outcome.
"""
import functools
import math

import numpy as np

TIE, FLAT, LIE = "tie", "flat", "Lie"
RESAMPLES = 2000
SEED = 31  # a fixed seed: the same report gives the same interval


def predictor(entry):
    """X = |ω0| / Ω of a regime cell or held-out scene (∞ where Ω = 0: no bowl); NaN without the rates."""
    omega0, frequency = entry.get("omega0"), entry.get("bowl_frequency")
    if not isinstance(omega0, (int, float)) or not isinstance(frequency, (int, float)):
        return math.nan
    return math.inf if frequency <= 0 else float(omega0) / float(frequency)


def outcome(ratio):
    """FLAT, LIE or TIE from a pairs.time_ratio tuple; None where there is none or it is only a bound."""
    median, low, high, repeats, bound = ratio
    if not math.isfinite(median) or median <= 0 or bound:
        return None
    if repeats > 1 and low <= 1.0 <= high:
        return TIE
    return LIE if median > 1.0 else FLAT


RIDGE = 0.01  # on the slope: keeps it finite where the outcomes separate perfectly


def _logistic(lx, won):
    """(intercept, slope) of P(Lie wins) = 1 / (1 + exp(−(a + b log10 X))) by Newton's method on the
    log-likelihood with RIDGE on b; None when one side never wins or the X do not vary (nothing to separate)."""
    if len(set(lx.tolist())) < 2 or won.min() == won.max():
        return None
    design = np.column_stack([np.ones_like(lx), lx])
    penalty = np.diag([0.0, RIDGE])
    w = np.zeros(2)
    for _ in range(200):
        p = 1.0 / (1.0 + np.exp(-(design @ w)))
        gradient = design.T @ (won - p) - penalty @ w
        hessian = design.T @ (design * (p * (1.0 - p))[:, None]) + penalty
        step = np.linalg.solve(hessian, gradient)
        w += step
        if np.abs(step).max() < 1e-12:
            break
    return float(w[0]), float(w[1])


def _crossing(line):
    """log10 x* where P = 1/2, None when P does not rise with X (no border to find)."""
    if line is None or not line[1] > 0:
        return None
    return -line[0] / line[1]


def fit(points, resamples=RESAMPLES, seed=SEED):
    """The crossover from [(cell, X, outcome)] (_fit; the same points give the same answer, computed once)."""
    return _fit(tuple(points), resamples, seed)


@functools.lru_cache(maxsize=16)
def _fit(points, resamples, seed):
    """The crossover from [(cell, X, outcome)]: the logistic fit of the Lie side winning (FLAT or LIE; ties and
    missing outcomes left out) on log10 X. A dict with x_star, low, high (NaN where P does not rise, or, for the
    interval, where under 97.5 % of the resamples that hold both sides find a crossing), slope (per decade of
    X), intercept, points, cells; None with fewer than two cells, one X value or one side only."""
    usable = [(c, x, o) for c, x, o in points if math.isfinite(x) and x > 0 and o in (FLAT, LIE)]
    cells = sorted({c for c, _, _ in usable})
    if len(cells) < 2:
        return None
    lx = np.log10([x for _, x, _ in usable])
    won = np.array([1.0 if o == LIE else 0.0 for _, _, o in usable])
    line = _logistic(lx, won)
    if line is None:
        return None
    rows = {c: [i for i, (cc, _, _) in enumerate(usable) if cc == c] for c in cells}
    rng = np.random.default_rng(seed)
    found, fitted = [], 0
    for _ in range(resamples):
        pick = np.concatenate([rows[cells[k]] for k in rng.integers(0, len(cells), len(cells))])
        resampled = _logistic(lx[pick], won[pick])
        if resampled is None:  # one side only: nothing to separate, no slope either way
            continue
        fitted += 1
        crossing = _crossing(resampled)
        if crossing is not None:
            found.append(crossing)
    centre = _crossing(line)
    low = high = math.nan
    if fitted and len(found) >= 0.975 * fitted:
        low, high = (10.0 ** float(q) for q in np.percentile(found, [2.5, 97.5]))
    return {"x_star": 10.0 ** centre if centre is not None else math.nan, "low": low, "high": high,
            "intercept": line[0], "slope": line[1], "points": len(usable), "cells": len(cells)}


def predict(x, result):
    """The predicted winner at X: LIE above x*, FLAT below; None without a crossover or X."""
    if result is None or not math.isfinite(result["x_star"]) or math.isnan(x):
        return None
    return LIE if x > result["x_star"] else FLAT


def check(entries, result):
    """[(entry, X, predicted, measured, hit)] over [(entry, ratio)] of held-out scene × target: hit True/False
    where both a prediction and a decided outcome (not a tie) exist, None otherwise."""
    rows = []
    for entry, ratio in entries:
        x = predictor(entry)
        predicted, measured = predict(x, result), outcome(ratio)
        hit = None if predicted is None or measured in (None, TIE) else predicted == measured
        rows.append((entry, x, predicted, measured, hit))
    return rows


def x_text(x):
    """X as a table shows it: ∞ on a plane, — where the report has no rates."""
    if math.isnan(x):
        return "—"
    return "∞" if math.isinf(x) else f"{x:.2g}"

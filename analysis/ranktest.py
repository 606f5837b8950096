"""Two-sided Mann–Whitney U test, NumPy only.

Timings are skewed and have outliers (a context switch, a cold cache), so
two sets of samples are compared by ranks, not by means. Small samples
without ties get the exact distribution of U (a normal approximation is too
coarse there: with 5 against 5 samples it can never reach p < 0.01); larger
samples, or any ties, get the normal approximation with tie correction and
continuity correction.
"""
import functools
import math

import numpy as np

# exact below this many samples per side (the table has n1 * n2 + 1 entries)
EXACT_MAX = 25


def average_ranks(values):
    """1-based ranks, tied values sharing the mean of their ranks."""
    values = np.asarray(values, float)
    order = np.argsort(values, kind="mergesort")
    ranks = np.empty(values.size)
    sorted_values = values[order]
    # boundaries of runs of equal values
    starts = np.flatnonzero(np.r_[True, sorted_values[1:] != sorted_values[:-1]])
    ends = np.r_[starts[1:], values.size]
    for s, e in zip(starts, ends):
        ranks[order[s:e]] = 0.5 * (s + 1 + e)
    return ranks, ends - starts


@functools.lru_cache(maxsize=None)
def _u_counts(n1, n2):
    """Number of orderings giving U = 0 .. n1 * n2 (no ties), as a tuple."""
    if n1 == 0 or n2 == 0:
        return (1,)
    counts = np.zeros(n1 * n2 + 1)
    # the largest value comes from sample 1 (adds n2 to U) or from sample 2 (adds nothing)
    a = np.array(_u_counts(n1 - 1, n2))
    counts[n2:n2 + a.size] += a
    b = np.array(_u_counts(n1, n2 - 1))
    counts[:b.size] += b
    return tuple(counts)


def mann_whitney(a, b):
    """(U of a, two-sided p) for "a and b come from the same distribution".

    p is 1.0 when either sample is empty (nothing can be concluded).
    """
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    a, b = a[np.isfinite(a)], b[np.isfinite(b)]
    n1, n2 = a.size, b.size
    if n1 == 0 or n2 == 0:
        return math.nan, 1.0
    ranks, tie_sizes = average_ranks(np.r_[a, b])
    u1 = ranks[:n1].sum() - n1 * (n1 + 1) / 2.0
    ties = bool((tie_sizes > 1).any())
    if not ties and n1 <= EXACT_MAX and n2 <= EXACT_MAX:
        counts = np.array(_u_counts(n1, n2))
        total = counts.sum()
        k = int(round(u1))
        lower = counts[:k + 1].sum() / total
        upper = counts[k:].sum() / total
        return float(u1), float(min(1.0, 2.0 * min(lower, upper)))
    n = n1 + n2
    mu = n1 * n2 / 2.0
    tie_term = float(((tie_sizes ** 3) - tie_sizes).sum())
    variance = n1 * n2 / 12.0 * ((n + 1) - tie_term / (n * (n - 1)))
    if variance <= 0:
        return float(u1), 1.0  # every value equal
    z = max(0.0, abs(u1 - mu) - 0.5) / math.sqrt(variance)
    return float(u1), float(min(1.0, math.erfc(z / math.sqrt(2.0))))

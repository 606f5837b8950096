"""The Lie frontier: on a scene, the best Lie-group method's wall time to a
target accuracy over the best library method's (Boost.Odeint, GSL, and the
peers SciPy and Octave when a report holds them). Below 1, the suite's best
method that keeps R on SO(3) beats every library there."""
import math

from analysis import costs, pairs
from analysis import report as rp

GOAL = 0.5  # issue 35's goal on the R-feeds-back scenes, at 1e-6 and 1e-9

# a bound on library / Lie is the opposite bound on Lie / library
_INVERTED_BOUND = {"≤": "≥", "≥": "≤", "~": "~", "": ""}


def sides(runs):
    """(Lie-group methods, library methods) among the runs, from each run's `on_group` and `family`."""
    lie, library = [], []
    for r in runs:
        side = lie if r.on_group else library if r.family in pairs.LIBRARY_FAMILIES else None
        if side is not None and r.integrator not in side:
            side.append(r.integrator)
    return lie, library


def cheapest(runs, names, metric, floor, target):
    """(cost, bound, name) of the name whose median wall time to reach target is least; None if none gets there."""
    reached = []
    of = rp.by_integrator(runs)
    for name in names:
        cost, bound = costs.reach(of.get(name, []), (target,), metric, floor)[target]
        if math.isfinite(cost):
            reached.append((cost, bound, name))
    return min(reached) if reached else None


def frontier(report, scene, metric, target):
    """(best Lie, best library, (median, low, high, repeats, bound) of Lie / library time), or None.

    The two best are picked by median wall time; the ratio is then read per
    timed repeat as pairs.time_ratio reads a pair, so its spread is the
    timing's, measured side by side.
    """
    runs = rp.runs(report, scene)
    floor = rp.floor(report, scene)
    lie, library = sides(runs)
    best_lie, best_library = (cheapest(runs, names, metric, floor, target) for names in (lie, library))
    if best_lie is None or best_library is None:
        return None
    lie_name, library_name = best_lie[2], best_library[2]
    median, low, high, repeats, bound = pairs.time_ratio(runs, library_name, lie_name, metric, floor, target)
    if not (math.isfinite(median) and median > 0 and low > 0 and high > 0):
        return None
    return lie_name, library_name, (1 / median, 1 / high, 1 / low, repeats, _INVERTED_BOUND.get(bound, bound))

"""One look for every figure: a colour per integrator family, and within a
family a marker, a line style and a shade per integrator.

The hue says the family, so a reader can compare families across figures at
a glance; the marker and line style tell the members of one family apart.
Both depend only on the names (never on plotting order), so the same
integrator looks the same in every figure of a report.
"""
import zlib

from matplotlib import colors as mcolors

# distinct hues for the families the suite ships; later families get one
# of the fallback hues, picked from the family name
FAMILY_COLOURS = {
    "rk": "#1f77b4",           # blue: classical Runge-Kutta on the flat view
    "rkmk": "#d62728",         # red: Lie-group (exp-Euler, Munthe-Kaas)
    "odeint": "#2ca02c",       # green: Boost.Odeint
    "gsl": "#9467bd",          # purple: GSL odeiv2
    "rkmk-adaptive": "#ff7f0e",  # orange: RKMK on embedded pairs
    "projection": "#8c564b",   # brown
    "quaternion": "#e377c2",   # pink
    "scipy": "#0fa3b1",        # cyan: SciPy solve_ivp, a peer (docs/peers.md)
    "octave": "#b8860b",       # dark gold: GNU Octave's ode45/ode23/ode15s, a peer
    "discrete-gradient": "#000000",  # black: dg2, the flat energy kept to rounding
    "nonholonomic-variational": "#6b8e23",  # olive: dla2, discrete Lagrange-d'Alembert
}
FALLBACK_COLOURS = ["#17becf", "#bcbd22", "#7f7f7f", "#393b79", "#637939", "#843c39", "#7b4173"]
UNKNOWN_FAMILY_COLOUR = "#555555"

MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*", "<", ">", "h", "p"]
LINESTYLES = ["-", "--", "-.", ":"]

# status colours for failure bars; "ok" is drawn light so failures stand out
STATUS_COLOURS = {
    "ok": "#d9d9d9", "diverged": "#d62728", "lift-off": "#ff7f0e", "curvature": "#bcbd22",
    "domain": "#17becf", "step-underflow": "#9467bd", "max-steps": "#8c564b",
    # an isolated plug-in's run that died, was killed at its limit, or left SO(3)
    "crashed": "#7f0000", "timeout": "#525252", "off-group": "#e377c2",
    "chart-limit": "#1f77b4",
    # an implicit method's Newton iteration that did not converge: the method's failure, not the model's
    "solver": "#7f7f00", "error": "#000000",
}


def _hash(name):
    # crc32 is stable across runs and Python versions, unlike hash()
    return zlib.crc32(name.encode("utf-8"))


def family_colour(family):
    if not family:
        return UNKNOWN_FAMILY_COLOUR
    if family in FAMILY_COLOURS:
        return FAMILY_COLOURS[family]
    return FALLBACK_COLOURS[_hash(family) % len(FALLBACK_COLOURS)]


def shade(colour, amount):
    """Mix with white (amount > 0) or black (amount < 0)."""
    r, g, b = mcolors.to_rgb(colour)
    target = 1.0 if amount > 0 else 0.0
    a = abs(amount)
    return (r + (target - r) * a, g + (target - g) * a, b + (target - b) * a)


class Palette:
    """Styles for a set of integrators {name: family}.

    Each integrator's preferred slot comes from a hash of its name; a taken
    slot moves on to the next free one, visiting names in sorted order, so
    that no two integrators of a family share marker and line style.
    """

    def __init__(self, families):
        self.families = dict(families)
        self._styles = {}
        by_family = {}
        for name, family in self.families.items():
            by_family.setdefault(family, []).append(name)
        slots = len(MARKERS) * len(LINESTYLES)
        for family, names in by_family.items():
            taken = set()
            names = sorted(names)
            for rank, name in enumerate(names):
                slot = _hash(name) % slots
                while slot in taken and len(taken) < slots:
                    slot = (slot + 1) % slots
                taken.add(slot)
                # up to +-25 % lighter or darker, spread over the family
                spread = 0.0 if len(names) == 1 else -0.25 + 0.5 * rank / (len(names) - 1)
                self._styles[name] = {
                    "color": shade(family_colour(family), spread),
                    "marker": MARKERS[slot % len(MARKERS)],
                    "linestyle": LINESTYLES[(slot // len(MARKERS)) % len(LINESTYLES)],
                }

    def family(self, name):
        return self.families.get(name)

    def style(self, name):
        """Keyword arguments for Axes.plot: color, marker, linestyle."""
        if name not in self._styles:
            slot = _hash(name) % (len(MARKERS) * len(LINESTYLES))
            return {"color": family_colour(self.families.get(name)), "marker": MARKERS[slot % len(MARKERS)],
                    "linestyle": LINESTYLES[slot // len(MARKERS)]}
        return dict(self._styles[name])

    def colour(self, name):
        return self.style(name)["color"]


def family_legend_handles(families):
    """Proxy artists, one per family present, for a 'colour = family' legend."""
    from matplotlib.patches import Patch
    return [Patch(color=family_colour(f), label=f if f else "unknown family")
            for f in sorted(set(families), key=lambda f: (f is None, f or ""))]

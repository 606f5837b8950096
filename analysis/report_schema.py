"""What each key of a report that the analysis reads must hold (docs/formats.md, "Report (JSON)").

check() walks the report against SCHEMA and raises SchemaError naming the
first key that does not fit: "runs[3].integrator is a number (7), expected
an integrator name". A key may be missing (unless report.REQUIRED lists
it, checked before this) and, except where a rule says otherwise, null;
keys the analysis does not read are not looked at. Numbers are int or
float, never true or false; a range is checked where the analysis relies
on it (errors, times and counts are >= 0, declared orders whole numbers up
to 100), while huge values are left to the figures, which leave out what a
plot cannot show (figures.PLOT_MAX). Scene and integrator names become
parts of file names (convergence-<scene>.png), so they must be safe
file-name components: a scene's name follows the rule rollbench applies
when it reads a scene (problems/safe_name.hpp), a method's the plug-in
rule (letters, digits and . _ + -). Entries of a list of objects are never
null, and a drift or horizon run's series hold one value per time. A bad
value is quoted short and escaped.
"""
import functools
import math
import re

# problems/safe_name.hpp: 1 to 64 letters, digits, '-', '_' or '.', not starting with '.'
SCENE_NAME = re.compile(r"[A-Za-z0-9_-][A-Za-z0-9._-]{0,63}")
SCENE_RULE = "1 to 64 letters, digits, '-', '_' or '.', not starting with '.'"
# a registry or plug-in name (integrators/steppers/plugin_stepper.cpp also allows '+')
METHOD_NAME = re.compile(r"[A-Za-z0-9_+-][A-Za-z0-9._+-]{0,127}")
METHOD_RULE = "1 to 128 letters, digits, '-', '_', '+' or '.', not starting with '.'"
ORDER_MAX = 100  # a declared order above this is not a method's
EXCERPT = 40     # characters of a bad value quoted in a message


class SchemaError(ValueError):
    """A key of the report holds what the analysis cannot read; the message names the key's path."""


def excerpt(value):
    """A short, printable quotation of a bad value: non-ASCII and control characters escaped, long text cut."""
    text = value if isinstance(value, str) else repr(value)
    out = text[:EXCERPT].encode("ascii", "backslashreplace").decode("ascii")
    out = "".join(c if " " <= c <= "~" else f"\\x{ord(c):02x}" for c in out)
    return out + ("..." if len(text) > EXCERPT else "")


def describe(value):
    """What a JSON value is, for a message: 'a number (7)', "a string ('12')", 'a list', 'null'."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return f"a number ({excerpt(value)})"
    if isinstance(value, str):
        return f"a string ('{excerpt(value)}')"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, dict):
        return "an object"
    return type(value).__name__


def _refuse(path, value, expected):
    raise SchemaError(f"{path} is {describe(value)}, expected {expected}")


class Spec:
    """One key's rule; nullable: null is accepted (a missing key always is, unless report.REQUIRED lists it)."""
    expected = "?"

    def __init__(self, nullable=True):
        self.nullable = nullable

    def check(self, value, path):
        if value is None:
            if not self.nullable:
                _refuse(path, value, self.expected)
            return
        self.check_value(value, path)

    def check_value(self, value, path):
        raise NotImplementedError


class Text(Spec):
    expected = "text"

    def check_value(self, value, path):
        if not isinstance(value, str):
            _refuse(path, value, self.expected)
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:  # a lone surrogate from a \\ud800 escape: no character
            raise SchemaError(f"{path} holds a \\u escape that is no character: '{excerpt(value)}'") from None


class Name(Text):
    """A scene or method name: text that is safe as a part of a file name."""

    def __init__(self, pattern, rule, what, nullable=False):
        super().__init__(nullable)
        self.pattern, self.rule, self.expected = pattern, rule, what

    def check_value(self, value, path):
        super().check_value(value, path)
        if not self.pattern.fullmatch(value):
            raise SchemaError(f"{path} is '{excerpt(value)}', not {self.expected} ({self.rule})")


def scene_name():
    return Name(SCENE_NAME, SCENE_RULE, "a scene name")


def method_name(nullable=False):
    return Name(METHOD_NAME, METHOD_RULE, "an integrator name", nullable)


class Number(Spec):
    """An int or float (not true/false) within [lo, hi] where given; whole: an integer value."""

    def __init__(self, lo=None, hi=None, whole=False, nullable=True):
        super().__init__(nullable)
        self.lo, self.hi, self.whole = lo, hi, whole
        kind = "a whole number" if whole else "a number"
        if lo is not None and hi is not None:
            kind += f" from {lo:g} to {hi:g}"
        elif lo is not None:
            kind += f" >= {lo:g}"
        self.expected = kind + (" or null" if nullable else "")

    def check_value(self, value, path):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            _refuse(path, value, self.expected)
        try:
            x = float(value)
        except OverflowError:  # an integer beyond the double's range
            raise SchemaError(f"{path} is a number out of range ({excerpt(value)})") from None
        if math.isnan(x):
            return  # not measured, as null
        if ((self.lo is not None and x < self.lo) or (self.hi is not None and x > self.hi)
                or (self.whole and math.isfinite(x) and x != math.floor(x))):
            _refuse(path, value, self.expected)


def at_least_0():
    return Number(lo=0)


class Flag(Spec):
    expected = "true or false"

    def check_value(self, value, path):
        if not isinstance(value, bool):
            _refuse(path, value, self.expected)


class ListOf(Spec):
    def __init__(self, item, nullable=True):
        super().__init__(nullable)
        self.item = item
        self.expected = "a list"

    def check_value(self, value, path):
        if not isinstance(value, list):
            _refuse(path, value, self.expected)
        entries = isinstance(self.item, (Obj, MapOf))  # a list's entries are objects, never null
        for i, x in enumerate(value):
            if x is None and entries:
                _refuse(f"{path}[{i}]", x, self.item.expected)
            self.item.check(x, f"{path}[{i}]")


class Obj(Spec):
    """An object whose listed keys follow their rules; other keys are not read, so not checked.

    series: (the times' key, the keys of the values at those times): each such list, where present, is as long as
    the times' (a drift or horizon run's series, drawn against its t)."""
    expected = "an object"

    def __init__(self, fields, nullable=True, series=None):
        super().__init__(nullable)
        self.fields, self.series = fields, series

    def check_value(self, value, path):
        if not isinstance(value, dict):
            _refuse(path, value, self.expected)
        for key, spec in self.fields.items():
            if key in value:  # a missing key reads as its default (or report.REQUIRED names it)
                spec.check(value[key], f"{path}.{key}" if path else key)
        if self.series:
            times, keys = self.series
            check_lengths(value, path, value.get(times) or [], times, keys)


def check_lengths(entry, path, times, times_key, keys):
    """Each list at keys of entry holds one value per time (or is missing)."""
    for key in keys:
        values = entry.get(key)
        if values is not None and len(values) != len(times):
            raise SchemaError(f"{path}.{key} holds {len(values)} values, but {times_key} holds {len(times)} times")


class MapOf(Spec):
    """An object whose every value follows one rule (per error component, per first integral)."""
    expected = "an object"

    def __init__(self, value, nullable=True):
        super().__init__(nullable)
        self.value = value

    def check_value(self, value, path):
        if not isinstance(value, dict):
            _refuse(path, value, self.expected)
        for key, x in value.items():
            self.value.check(x, f"{path}.{excerpt(key)}")


class Interval(Spec):
    """A 95 % interval: its half-width, or [low, high] (docs/formats.md, orders' ci95)."""
    expected = "a number >= 0, [low, high] or null"

    def check_value(self, value, path):
        if isinstance(value, list):
            if len(value) != 2:
                _refuse(path, value, self.expected)
            for i, x in enumerate(value):
                Number().check(x, f"{path}[{i}]")
            return
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            _refuse(path, value, self.expected)
        Number(lo=0).check_value(value, path)


class Errors(Spec):
    """A run's errors (error, error_max, error_grid): each component the report lists, worst and floor a number
    >= 0 or null, below_floor a list of names, reference text; other keys are not read, so not checked."""
    expected = "an object"

    def __init__(self, components, nullable=True):
        super().__init__(nullable)
        self.keys = {**{c: Number(lo=0) for c in (*components, "worst", "floor")},
                     "reference": Text(), "below_floor": ListOf(Text())}

    def check_value(self, value, path):
        if not isinstance(value, dict):
            _refuse(path, value, self.expected)
        for key, spec in self.keys.items():
            if key in value:
                spec.check(value[key], f"{path}.{key}")


def _growth():
    return Obj({"p_early": Number(), "p_late": Number(), "exponential": Flag()})


def _growth_fit():
    """A horizon run's fit of one series (bench/lib/horizon.cpp, fit_json): its class and per-decade slopes."""
    return Obj({"class": Text(), "reason": Text(), "p": Number(), "ci95": at_least_0(),
                "log10_c": Number(), "t_from": at_least_0(), "t_to": at_least_0(), "points": at_least_0(),
                "largest": at_least_0(), "rounding_level": at_least_0(), "at_rounding": Flag(),
                "decades": ListOf(Obj({"t_from": at_least_0(), "t_to": at_least_0(), "p": Number(),
                                       "ci95": at_least_0(), "points": at_least_0()})),
                "p_earlier": Number(), "ci95_earlier": at_least_0(), "p_last": Number(), "ci95_last": at_least_0()})


def _series_values():
    """One number >= 0 (or null) per horizon series: an earlier run's largest values."""
    return {key: at_least_0() for key in ("energy_error", "energy_error_on_group", "rotation_defect")}


def _order_fit():
    return Obj({"points": at_least_0(), "at_plateau": at_least_0(), "halving_slopes": ListOf(Number()),
                "rung_slopes": ListOf(Number()), "asymptotic": Flag(), "all_at_plateau": Flag(),
                "slope": Number(), "ci95": Interval(), "h_min": at_least_0(), "h_max": at_least_0(),
                "r2": Number(), "residual": Number(), "trend_slopes": ListOf(Number()), "trend": Number(),
                "trend_ci95": Interval()})


def _order():
    return Number(lo=0, hi=ORDER_MAX, whole=True)


def _numbers():
    return ListOf(Number())


def _status():
    """A run's status: text; where the key may be missing (read as "ok"), never null."""
    return Text(nullable=False)


class HorizonRun(Obj):
    """A horizon run: its series and each first integral's error hold one value per time in t."""

    def check_value(self, value, path):
        super().check_value(value, path)
        for i, invariant in enumerate(value.get("invariants") or []):
            check_lengths(invariant, f"{path}.invariants[{i}]", value.get("t") or [], "t", ("error",))


def _run(components):
    errors = Errors(components)
    return Obj({
        "scene": scene_name(), "integrator": method_name(), "family": Text(), "adaptive": Flag(nullable=False),
        "status": _status(), "message": Text(), "declared_order": _order(), "declared_rotation_order": _order(),
        "tableau": Text(), "controller": Text(), "on_group": Flag(), "h": at_least_0(), "rtol": at_least_0(),
        "atol": at_least_0(), "t_end": at_least_0(), "stop_time": at_least_0(), "steps": at_least_0(),
        "rejected": at_least_0(), "rhs_evals": at_least_0(), "rhs_equivalents": at_least_0(),
        "jacobian_evals": at_least_0(), "exp_evals": at_least_0(), "dexpinv_evals": at_least_0(),
        "validity_checks": at_least_0(), "timed_outputs": at_least_0(),
        "wall_s": Obj({"median": at_least_0(), "min": at_least_0(), "max": at_least_0(), "repeats": at_least_0(),
                       "samples": ListOf(at_least_0())}),
        "error": errors, "error_max": errors, "error_grid": errors,
        "drift": Obj({"energy": at_least_0(), "energy_on_group": at_least_0(), "rotation_defect": at_least_0()}),
        "reversibility": Obj({"status": _status(), "message": Text(), "contact": at_least_0(),
                              "rotation": at_least_0(), "momentum": at_least_0(), "worst": at_least_0()}),
        "peer": Obj({"declared_order_text": Text(), "name": Text(), "method": Text()}),
    })


REFERENCE = Obj({
    "scene": scene_name(), "kind": Text(), "method": Text(), "cross_check": Text(), "error": at_least_0(),
    "component_errors": MapOf(at_least_0()), "t_end": at_least_0(), "omega_scale": at_least_0(),
    "inertia": _numbers(), "r_feeds_back": Flag(), "message": Text(),
})

ORDER = Obj({
    "scene": scene_name(), "integrator": method_name(), "declared": _order(), "declared_rotation": _order(),
    "observed": MapOf(Number()), "ci95": MapOf(Interval()), "fit": _order_fit(), "fits": MapOf(_order_fit()),
    "verdict": MapOf(Text()), "inconclusive_reason": MapOf(Text()), "pass": Flag(),
})

TOLERANCE_FIT = Obj({
    "scene": scene_name(), "integrator": method_name(), "slope": Number(), "intercept": Number(),
    "residual": Number(), "ci95": at_least_0(), "points": at_least_0(),
    "step_order": Obj({"slope": Number(), "ci95": at_least_0(), "residual": Number(), "points": at_least_0()}),
})

SERIES = ("t", ("energy_error", "energy_error_on_group", "rotation_defect"))  # a drift or horizon run's, at its t

DRIFT_RUN = Obj({
    "scene": scene_name(), "integrator": method_name(), "family": Text(), "h": at_least_0(), "status": _status(),
    "message": Text(), "stop_time": at_least_0(), "t": ListOf(at_least_0()), "energy_error": ListOf(at_least_0()),
    "energy_error_on_group": ListOf(at_least_0()), "rotation_defect": ListOf(at_least_0()), "steps": at_least_0(),
    "rhs_evals": at_least_0(), "rhs_equivalents": at_least_0(), "wall_s": at_least_0(),
}, series=SERIES)

STABLE_STEP = Obj({
    "scene": scene_name(), "integrator": method_name(), "family": Text(), "h": at_least_0(),
    "horizon": at_least_0(), "at_limit": Flag(), "energy_error": at_least_0(),
    "energy_error_on_group": at_least_0(), "rotation_defect": at_least_0(), "energy_scale": at_least_0(),
    "thresholds": MapOf(Number()),
    "tried": ListOf(Obj({"h": at_least_0(), "status": _status(), "message": Text(), "stop_time": at_least_0(),
                         "energy_error": at_least_0(), "energy_error_on_group": at_least_0(),
                         "rotation_defect": at_least_0(),
                         "growth": Obj({"energy_error": _growth(), "rotation_defect": _growth()}),
                         "failure": Text(), "stable": Flag()})),
    # the two limits (analysis/stability.py), one entry per horizon
    "horizons": ListOf(at_least_0()),
    "blow_up": Obj({"same_at_every_horizon": Flag(),
                    "at": ListOf(Obj({"horizon": at_least_0(), "h": at_least_0(), "cause": Text(), "status": Text(),
                                      "smallest_tried": Flag()}))}),
    "drift_limited": ListOf(Obj({"horizon": at_least_0(), "h": at_least_0(), "at_limit": Flag(),
                                 "next_h": at_least_0(), "limited_by": Text(), "blow_up": Text(), "status": Text(),
                                 "value": Number(), "bound": Number()})),
})

HORIZON_RUN = HorizonRun({
    "scene": scene_name(), "integrator": method_name(), "family": Text(), "r_feeds_back": Flag(),
    "declared_order": _order(), "on_group": Flag(), "coarsening": Number(lo=1), "h": at_least_0(),
    "steps_planned": at_least_0(), "study_steps": at_least_0(), "t_end": at_least_0(), "status": _status(),
    "message": Text(), "budget_ran_out": Flag(), "budget_reason": Text(),
    "earlier_runs": ListOf(Obj({"steps": at_least_0(), "t_end": at_least_0(), "status": _status(),
                                "cpu_s": at_least_0(), "wall_s": at_least_0(), "largest": Obj(_series_values()),
                                "class": Obj({key: Text() for key in _series_values()})})),
    "stop_time": at_least_0(), "steps": at_least_0(), "rhs_evals": at_least_0(), "rhs_equivalents": at_least_0(),
    "wall_s": at_least_0(), "cpu_s": at_least_0(), "energy_scale": at_least_0(), "t": ListOf(at_least_0()),
    "energy_error": ListOf(at_least_0()), "energy_error_on_group": ListOf(at_least_0()),
    "rotation_defect": ListOf(at_least_0()),
    "fit": Obj({key: _growth_fit() for key in ("energy_error", "energy_error_on_group", "rotation_defect")}),
    "invariants": ListOf(Obj({"name": Text(), "kind": Text(), "error": ListOf(at_least_0()), "fit": _growth_fit()})),
    "same_as": Obj({**{key: method_name(nullable=True)
                       for key in ("energy_error", "energy_error_on_group", "rotation_defect")},
                    "invariants": MapOf(method_name(nullable=True))}),
}, series=SERIES)

REGIME_AXES = ("inertia", "spin", "roughness", "t_end", "bowl", "speed")
REGIME_SCENE = Obj({
    "scene": scene_name(), "kind": Text(), "inertia": Number(), "spin": Number(), "roughness": Number(),
    "t_end": Number(), "bowl": Number(), "speed": Number(), "moments": _numbers(), "amplitude": Number(),
    "contact": _numbers(), "omega0": Number(), "bowl_frequency": Number(), "spin_ratio": Number(),
})


@functools.lru_cache(maxsize=8)
def schema(components):
    """The whole report's rules, for the error components a report lists (their names are keys of its errors)."""
    return Obj({
        "created": Text(), "git": Text(), "preset": Text(),
        "machine": Obj({"cpu": Text(), "cores": at_least_0(), "os": Text(), "load": _numbers()}),
        "build": Obj({"compiler": Text(), "flags": Text(), "type": Text()}),
        "options": Obj({"scenes": ListOf(Text()), "integrators": ListOf(Text()), "h": _numbers(), "tol": _numbers(),
                        "t_end": at_least_0(), "dt_out": at_least_0(), "error_dt": at_least_0(),
                        "horizon": Obj({"asymptotic_spread": Number()})}),
        "error_components": ListOf(Obj({"name": Name(SCENE_NAME, SCENE_RULE, "a component name"),
                                        "label": Text(nullable=False), "unit": Text(nullable=False),
                                        "scale": Text()})),
        "references": ListOf(REFERENCE),
        "runs": ListOf(_run(components)),
        "orders": ListOf(ORDER),
        "tolerance_fits": ListOf(TOLERANCE_FIT),
        "stability": Obj({"drift": ListOf(DRIFT_RUN), "largest_stable_h": ListOf(STABLE_STEP)}),
        "horizon": Obj({"runs": ListOf(HORIZON_RUN)}),
        "regime": Obj({"axes": Obj({axis: _numbers() for axis in REGIME_AXES}),
                       "cells": ListOf(REGIME_SCENE), "held_out": ListOf(REGIME_SCENE)}),
    }, nullable=False)


def check(report):
    """Raises SchemaError at the first key of the report that does not fit its schema()."""
    components = tuple(c["name"] for c in report.get("error_components") or []
                       if isinstance(c, dict) and isinstance(c.get("name"), str))
    schema(components).check(report, "")

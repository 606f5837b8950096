"""Reading rollbench reports (docs/formats.md, "Report (JSON)").

load() reads the file as analysis/safe_files.py reads every input (a
regular file of UTF-8 within its limit), parses it within the JSON limits
rollbench's own readers keep (analysis/json_limits.py: 64 levels, no NaN,
numbers within a double), checks the schema string and the keys the analysis relies on, and
then the type and range of every key it reads (analysis/report_schema.py);
each failure is a ReportError that names the file and the key. Other keys
are optional, and sections (orders, stability, references) may be missing
or empty. The accessors below turn the report's nulls into NaN so that the
figures and tables can treat "not measured" uniformly.
"""
import contextlib
import dataclasses
import math

import numpy as np

from analysis import json_limits, report_schema, safe_files

SCHEMA = "rollbench.report/2"
# "worst" (the largest of the error components, each made dimensionless) is
# the only accuracy axis that sees R everywhere; the components themselves
# come from the report (components())
DEFAULT_METRIC = "worst"
WORST_LABEL = "worst error (ball radii or rad)"

# keys without which an entry of a section means nothing
REQUIRED = {
    "runs": ("scene", "integrator", "family", "adaptive", "status"),
    "orders": ("scene", "integrator"),
    "references": ("scene",),
    "stability.drift": ("scene", "integrator", "t"),
    "stability.largest_stable_h": ("scene", "integrator", "h", "tried"),
    "tolerance_fits": ("scene", "integrator", "slope"),
}


class ReportError(ValueError):
    """A file that is not a usable report; the message names the key."""


def load(path):
    try:
        # a regular file of UTF-8 within the limit (analysis/safe_files.py): a FIFO or /dev/zero is refused at once
        text = safe_files.read_text(path, "report", safe_files.REPORT_LIMIT)
    except safe_files.InputFileError as e:
        raise ReportError(str(e)) from None
    try:
        # at most 64 levels, no NaN, numbers within a double: as rollbench's own readers (analysis/json_limits.py)
        data = json_limits.parse(text, safe_files.shown(path))
    except json_limits.JsonError as e:
        raise ReportError(str(e)) from None
    # the path in messages as shown, its control characters and non-ASCII bytes escaped, without the quotes
    return validate(data, safe_files.shown(path)[1:-1])


def validate(data, name="report"):
    """The report itself, once it has passed the checks; raises ReportError."""
    if not isinstance(data, dict):
        raise ReportError(f"{name}: a report is a JSON object, not {type(data).__name__}")
    if "schema" not in data:
        raise ReportError(f"{name}: missing key 'schema' (expected \"{SCHEMA}\")")
    if data["schema"] != SCHEMA:
        found = f"'{report_schema.excerpt(data['schema'])}'" if isinstance(data["schema"], str) else \
            report_schema.describe(data["schema"])
        raise ReportError(f"{name}: schema version {found} found, this analysis reads only "
                          f"\"{SCHEMA}\" (re-run rollbench to write a current report)")
    for section, keys in REQUIRED.items():
        entries = section_entries(data, section, name)
        for i, entry in enumerate(entries):
            if not isinstance(entry, dict):
                raise ReportError(f"{name}: {section}[{i}] is not an object")
            for key in keys:
                if key not in entry:
                    raise ReportError(f"{name}: {section}[{i}] has no key '{key}'")
    if "error_components" not in data:
        raise ReportError(f"{name}: missing key 'error_components' (the components of a run's error; "
                          "re-run rollbench to write a current report)")
    entries = data["error_components"]
    if not isinstance(entries, list) or not entries:
        raise ReportError(f"{name}: key 'error_components' is not a list of components")
    for i, entry in enumerate(entries):
        for key in ("name", "label", "unit"):
            if not isinstance(entry, dict) or not isinstance(entry.get(key), str):
                raise ReportError(f"{name}: error_components[{i}] has no text key '{key}'")
    try:
        report_schema.check(data)
    except report_schema.SchemaError as e:
        raise ReportError(f"{name}: {e}") from None
    for i, run in enumerate(data.get("runs") or []):
        if not run["adaptive"] and run.get("h") is None and run["status"] == "ok":
            raise ReportError(f"{name}: runs[{i}] is a fixed-step run with no key 'h'")
    return data


def section_entries(data, section, name="report"):
    """The list at a dotted path ('stability.drift'), [] when it is absent or null."""
    node = data
    for part in section.split("."):
        if node is None:
            return []
        if not isinstance(node, dict):
            raise ReportError(f"{name}: '{section}' is not inside an object")
        node = node.get(part)
    if node is None:
        return []
    if not isinstance(node, list):
        raise ReportError(f"{name}: key '{section}' is not a list")
    return node


def components(report):
    """The names of the error components, in the report's order (its "error_components")."""
    return tuple(c["name"] for c in report["error_components"])


def metrics(report):
    """The accuracy axes a figure or table can use: "worst", then every component."""
    return (DEFAULT_METRIC,) + components(report)


def metric_label(report, metric):
    """An axis label for a metric: its label and unit ("contact-point error (m)")."""
    if metric == "worst":
        return WORST_LABEL
    for c in report["error_components"]:
        if c["name"] == metric:
            return f"{c['label']} ({c['unit']})"
    raise ReportError(f"no error component '{metric}' in the report (it has {', '.join(components(report))})")


def num(value):
    """A float, NaN for null or anything that is not a number."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return math.nan
    return float(value)


def unique(items):
    """Items in order of first appearance."""
    seen, out = set(), []
    for item in items:
        if item not in seen:
            seen.add(item)
            out.append(item)
    return out


# -- sections ------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Run:
    """One entry of the report's `runs` (docs/formats.md, "A run") as a record.

    The method's facts and the run's setting, status and cost are fields
    (a number the report leaves null is NaN); `entry` is the report's object
    itself, for what the accessors below read from it (the errors, the
    timing samples) and the sections one reader needs (drift,
    reversibility). Made by runs(), never by hand.
    """
    scene: str
    integrator: str
    family: str | None
    adaptive: bool
    status: str
    on_group: bool
    declared_order: int | None
    tableau: str | None
    controller: str | None
    h: float
    rtol: float
    atol: float
    rhs_evals: float
    stop_time: float
    message: str
    entry: dict = dataclasses.field(repr=False, compare=False)

    @classmethod
    def of(cls, entry):
        return cls(scene=entry["scene"], integrator=entry["integrator"], family=entry.get("family"),
                   adaptive=bool(entry["adaptive"]), status=entry["status"], on_group=bool(entry.get("on_group")),
                   declared_order=entry.get("declared_order"), tableau=entry.get("tableau") or None,
                   controller=entry.get("controller"), h=num(entry.get("h")), rtol=num(entry.get("rtol")),
                   atol=num(entry.get("atol")), rhs_evals=num(entry.get("rhs_evals")),
                   stop_time=num(entry.get("stop_time")), message=entry.get("message") or "", entry=entry)


def runs(report, scene=None, adaptive=None):
    """The runs as Run records, in the report's order; those of one scene, or of one adaptivity, when given."""
    out = section_entries(report, "runs")
    if scene is not None:
        out = [r for r in out if r["scene"] == scene]
    if adaptive is not None:
        out = [r for r in out if bool(r["adaptive"]) == adaptive]
    return [Run.of(r) for r in out]


def by_integrator(records):
    """{integrator: its runs (or entries of another section)}, in order of first appearance."""
    out = {}
    for r in records:
        out.setdefault(r.integrator if isinstance(r, Run) else r["integrator"], []).append(r)
    return out


def drift_runs(report, scene=None):
    out = section_entries(report, "stability.drift")
    return [d for d in out if scene is None or d["scene"] == scene]


def stable_steps(report):
    return section_entries(report, "stability.largest_stable_h")


def stable_h(entry):
    """The largest stable step of a stability entry (NaN when none passes)."""
    return num(entry.get("h"))


def tested_h(entry):
    """Every step the stability study tried for this entry."""
    return [num(t.get("h")) for t in entry.get("tried") or []]


def scenes(report):
    """Every scene the report mentions, in order of first appearance."""
    names = [r.scene for r in runs(report)]
    names += [d["scene"] for d in drift_runs(report)]
    names += [s["scene"] for s in stable_steps(report)]
    return unique(names)


def integrators(entries):
    """Integrator names of some runs (Run records or another section's entries), in order of first appearance."""
    return list(by_integrator(entries))


def families(report):
    """{integrator: family} over every section."""
    out = {}
    for run in runs(report):
        out.setdefault(run.integrator, run.family)
    for entry in drift_runs(report) + stable_steps(report) + section_entries(report, "horizon.runs"):
        out.setdefault(entry["integrator"], entry.get("family"))
    return out


def reference(report, scene):
    for ref in section_entries(report, "references"):
        if ref["scene"] == scene:
            return ref
    return None


def floor(report, scene):
    """The reference's own error for a scene (0 when unknown): errors below it are not measured."""
    ref = reference(report, scene)
    value = num(ref.get("error")) if ref else math.nan
    if not math.isfinite(value):
        floors = [num((r.entry.get("error") or {}).get("floor")) for r in runs(report, scene)]
        floors = [f for f in floors if math.isfinite(f)]
        value = max(floors) if floors else 0.0
    return value


# which of a run's errors the figures and tables read: "error" (at t_end) or
# "error_max" (the largest over the timed run's steps); plot.py --errors
ERROR_KEYS = {"end": "error", "max": "error_max"}
_error_key = "error"


def use_errors(kind):
    """Read the errors at t_end ("end", the default) or the largest over the run ("max") from now on."""
    global _error_key
    _error_key = ERROR_KEYS[kind]


@contextlib.contextmanager
def errors_read(kind):
    """Read kind's errors ("end" or "max") inside the block, then the earlier choice again."""
    global _error_key
    before, _error_key = _error_key, ERROR_KEYS[kind]
    try:
        yield
    finally:
        _error_key = before


def error(run, component=DEFAULT_METRIC):
    """A Run's error in a component (or "worst"), as errors_read chose: at t_end or the largest over the run."""
    return num((run.entry.get(_error_key) or {}).get(component))


def below_floor(run, component=DEFAULT_METRIC):
    return component in ((run.entry.get(_error_key) or {}).get("below_floor") or [])


def wall(run):
    """A Run's wall time, the median over its timed repeats."""
    return num((run.entry.get("wall_s") or {}).get("median"))


def samples(run):
    raw = (run.entry.get("wall_s") or {}).get("samples") or []
    return np.array([num(s) for s in raw if math.isfinite(num(s))], dtype=float)


def ok(run):
    return run.status == "ok"


def tolerance(run):
    return run.rtol


def setting(run, digits=6):
    """The run's step size or tolerances, as text (its place in a sweep)."""
    if run.adaptive:
        if math.isfinite(run.atol) and run.atol != run.rtol:
            return f"rtol={run.rtol:.{digits}g} atol={run.atol:.{digits}g}"
        return f"tol={run.rtol:.{digits}g}"
    return f"h={run.h:.{digits}g}"


# -- orders --------------------------------------------------------------------

def orders(report):
    """Entries of "orders", as the runner fitted them (never refitted here)."""
    return section_entries(report, "orders")


def tolerance_fits(report, scene=None):
    return [f for f in section_entries(report, "tolerance_fits") if scene is None or f["scene"] == scene]


def order_of(report, scene, integrator):
    for o in orders(report):
        if o["scene"] == scene and o["integrator"] == integrator:
            return o
    return None


def observed(order, component):
    if not order:
        return math.nan
    return num((order.get("observed") or {}).get(component))


def verdict(order, component):
    """'as declared', 'lower', 'exact' or 'inconclusive' as the runner decided; '—' when absent."""
    value = (order.get("verdict") or {}).get(component) if order else None
    return value if isinstance(value, str) and value else "—"

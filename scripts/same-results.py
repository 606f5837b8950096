#!/usr/bin/python3
"""Whether a change kept the suite's results bit for bit: for a refactor or a speed-up that must not move a number.

    scripts/same-results.py BASE NEW [--methods REGEX] [--scenes A,B,...] [--t-end T] [--jobs N]
    scripts/same-results.py --reports A.json B.json

The first form runs every registered method (or those whose name matches REGEX) of two rollbench binaries, BASE
(built before the change) and NEW, on each scene at two settings (fixed steps h = 0.01 and 0.002, adaptive
tolerances 1e-5 and 1e-8, the trajectory to T, default 3, a row every 0.1) and compares the runs: the exit status,
the printed text and the trajectory CSV, byte for byte. The scenes default to six shipped ones that between them
cover both balls, long runs and curved landscapes; a scene may also be a JSON file (a landscape that throws the
ball off, say, to compare the stops). The environment passes through, so that `RB_NATIVE_FORMULA=off` compares the
tape's results.

The second form compares two reports of `rollbench run` (the same preset before and after): every value the same
bit for bit, the timings (every `wall_s`), the report's creation time, its commit and the machine's state aside.

Prints each difference and a count; exit status 0 when everything is the same, 1 when something differs, 2 for
bad arguments, a binary that cannot be run or a report that cannot be read (analysis/report.py's checks)."""
import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import tempfile

if __package__ in (None, ""):
    sys.path[0] = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

from analysis import report as rp  # noqa: E402

SCENES = "valley-sideways,bumpy-long,chaplygin-bumpy-long,saddle,paraboloid-perturbed,gaussian-hills"
SETTINGS = {"fixed": (["--h", "0.01"], ["--h", "0.002"]),
            "adaptive": (["--rtol", "1e-5", "--atol", "1e-5"], ["--rtol", "1e-8", "--atol", "1e-8"])}
RUN_TIMEOUT_S = 600
# what a report may change without a result changing: when and where it was made, and how long it took
REPORT_METADATA = {"created", "git", "machine"}
TIMING_KEY = "wall_s"
SHOWN = 20  # report differences printed at most


class Unreadable(Exception):
    pass


def methods_of(rollbench):
    """{name: 'fixed' or 'adaptive'} from the registry's table (`rollbench list --markdown`)."""
    try:
        p = subprocess.run([rollbench, "list", "--markdown"], capture_output=True, text=True, timeout=120)
    except OSError as e:
        raise Unreadable(f"{rollbench}: {e.strerror}") from e
    if p.returncode:
        raise Unreadable(f"{rollbench} list --markdown: exit status {p.returncode}: {p.stderr.strip()[-300:]}")
    rows = {}
    for line in p.stdout.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 4 and cells[3] in SETTINGS:
            rows[cells[0]] = cells[3]
    if not rows:
        raise Unreadable(f"{rollbench} list --markdown: no method table in its output")
    return rows


def run_once(rollbench, method, scene, setting, t_end, out):
    """(exit status, printed text with the CSV's path replaced, CSV bytes or None)."""
    args = [rollbench, "trajectory", scene, "--integrator", method, "--t-end", t_end, "--dt-out", "0.1",
            "--out", out] + setting
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return ("timeout", "", None)
    text = (p.stdout + p.stderr).replace(out, "OUT")
    data = None
    if os.path.exists(out):
        with open(out, "rb") as f:
            data = f.read()
    return (p.returncode, text, data)


def first_differing_line(a, b):
    la, lb = a.splitlines(), b.splitlines()
    return next((i + 1 for i, (x, y) in enumerate(zip(la, lb)) if x != y), min(len(la), len(lb)) + 1)


def difference(base, new):
    """What differs between two runs' outcomes, or None."""
    (rc_a, text_a, csv_a), (rc_b, text_b, csv_b) = base, new
    if rc_a != rc_b:
        return f"exit status {rc_a} -> {rc_b}"
    if text_a != text_b:
        return f"the printed text, from line {first_differing_line(text_a, text_b)}"
    if (csv_a is None) != (csv_b is None):
        return "the CSV written by one only"
    if csv_a != csv_b:
        return f"the CSV, from line {first_differing_line(csv_a, csv_b)}"
    return None


def compare_binaries(args):
    try:
        base_methods, new_methods = methods_of(args.base), methods_of(args.new)
    except Unreadable as e:
        print(f"same-results: {e}", file=sys.stderr)
        return 2
    try:
        pattern = re.compile(args.methods)
    except re.error as e:
        print(f"same-results: --methods {args.methods!r}: {e}", file=sys.stderr)
        return 2
    differ = 0
    for name in sorted(set(base_methods) ^ set(new_methods)):
        if pattern.search(name):
            print(f"different: {name} is registered in {'BASE' if name in base_methods else 'NEW'} only")
            differ += 1
    methods = [(n, k) for n, k in new_methods.items() if n in base_methods and pattern.search(n)]
    scenes = [s for s in args.scenes.split(",") if s]
    if not methods or not scenes:
        print(f"same-results: no runs: {len(methods)} methods match {args.methods!r}, {len(scenes)} scenes",
              file=sys.stderr)
        return 2
    jobs = [(name, scene, setting) for name, kind in methods for scene in scenes for setting in SETTINGS[kind]]
    stopped = differ_runs = 0
    with tempfile.TemporaryDirectory(prefix="rb-same-results-") as tmp:
        def one(numbered):
            i, (name, scene, setting) = numbered
            base = run_once(args.base, name, scene, setting, args.t_end, os.path.join(tmp, f"{i}-base.csv"))
            new = run_once(args.new, name, scene, setting, args.t_end, os.path.join(tmp, f"{i}-new.csv"))
            return base[0], difference(base, new)

        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            for (name, scene, setting), (status, what) in zip(jobs, pool.map(one, enumerate(jobs))):
                stopped += status != 0
                if what:
                    differ_runs += 1
                    print(f"different: {name} on {scene} with {' '.join(setting)}: {what}", flush=True)
    print(f"{len(jobs)} runs ({len(methods)} methods x {len(scenes)} scenes x 2 settings; {stopped} of them "
          f"ended with a non-zero exit status in BASE): {len(jobs) - differ_runs} the same, {differ_runs} different")
    differ += differ_runs
    return 1 if differ else 0


def same_value(a, b):
    """Bit for bit: a float's repr is unique to its bits (so -0.0 is not 0.0, and NaN is NaN); 1 is not 1.0."""
    return type(a) is type(b) and (repr(a) == repr(b) if isinstance(a, float) else a == b)


def report_differences(a, b, path=""):
    """The paths (runs[3].error) where two reports' values differ, timings and metadata aside."""
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key == TIMING_KEY or (not path and key in REPORT_METADATA):
                continue
            where = f"{path}.{key}" if path else key
            if key not in a or key not in b:
                yield f"{where}: in {'B' if key in b else 'A'} only"
            else:
                yield from report_differences(a[key], b[key], where)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            yield f"{path}: {len(a)} entries -> {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            yield from report_differences(x, y, f"{path}[{i}]")
    elif not same_value(a, b):
        yield f"{path}: {json.dumps(a)[:80]} -> {json.dumps(b)[:80]}"


def compare_reports(paths):
    try:
        a, b = (rp.load(p) for p in paths)
    except rp.ReportError as e:
        print(f"same-results: {e}", file=sys.stderr)
        return 2
    found = list(report_differences(a, b))
    for line in found[:SHOWN]:
        print(f"different: {line}")
    if len(found) > SHOWN:
        print(f"... and {len(found) - SHOWN} more")
    runs = len(a.get("runs") or [])
    print(f"{paths[0]} and {paths[1]} ({runs} runs): "
          + (f"{len(found)} values different" if found else "the same, timings aside"))
    return 1 if found else 0


def main(argv):
    parser = argparse.ArgumentParser(prog="same-results.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("base", nargs="?", help="the rollbench binary built before the change")
    parser.add_argument("new", nargs="?", help="the rollbench binary built after it")
    parser.add_argument("--methods", default=".", help="a regular expression on the registry names (default: all)")
    parser.add_argument("--scenes", default=SCENES, help=f"comma-separated scene names or JSON files ({SCENES})")
    parser.add_argument("--t-end", default="3", help="end time of every run (default 3)")
    parser.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    parser.add_argument("--reports", nargs=2, metavar=("A.json", "B.json"), help="compare two reports instead")
    args = parser.parse_args(argv)
    if args.reports:
        if args.base or args.new:
            parser.error("--reports takes two reports, and no binaries")
        return compare_reports(args.reports)
    if not (args.base and args.new):
        parser.error("BASE and NEW, two rollbench binaries, are needed (or --reports A.json B.json)")
    if args.jobs < 1:
        parser.error(f"--jobs must be at least 1, not {args.jobs}")
    return compare_binaries(args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

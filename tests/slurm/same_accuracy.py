#!/usr/bin/python3
"""Do two rollbench reports agree in every accuracy field?

    tests/slurm/same_accuracy.py WHOLE.json MERGED.json

Compares everything but what is timing or provenance of one process (wall
times, the creation time, the machine): errors, orders and their fits,
statuses, step and evaluation counts, references, the stability study and
the sweep's options (except the thread count). Prints the first difference, exits 1 on one.
"""
import json
import sys

# fields that differ between two runs of the same sweep
NOT_ACCURACY = {"created", "machine", "wall_s"}
# options that change how a sweep runs, not what it computes
NOT_ACCURACY_OPTIONS = {"jobs"}


def without_timing(value):
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k not in NOT_ACCURACY}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


def first_difference(a, b, path="report"):
    if type(a) is not type(b):
        return f"{path}: {a!r} against {b!r}"
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{path}.{key}: present in only one report"
            found = first_difference(a[key], b[key], f"{path}.{key}")
            if found:
                return found
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} entries against {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_difference(x, y, f"{path}[{i}]")
            if found:
                return found
        return None
    return None if a == b else f"{path}: {a!r} against {b!r}"


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        whole = without_timing(json.load(f))
    with open(argv[2]) as f:
        merged = without_timing(json.load(f))
    for report in (whole, merged):
        for key in NOT_ACCURACY_OPTIONS:
            report.get("options", {}).pop(key, None)
    if not whole.get("runs"):
        print(f"{argv[1]}: no runs to compare", file=sys.stderr)
        return 1
    found = first_difference(whole, merged)
    if found:
        print(f"the reports differ at {found}", file=sys.stderr)
        return 1
    print(f"same accuracy: {len(whole['runs'])} runs, {len(whole.get('orders', []))} order fits")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

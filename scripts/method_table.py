#!/usr/bin/python3
"""Writes the registry's method table (`rollbench list --markdown`) into docs/integrators.md between its two marker
lines, so that the table is never written by hand: `scripts/method_table.py [ROLLBENCH]` rewrites the block,
`--check` only says whether it is current (exit 1 with the first differing line when not). ROLLBENCH defaults to
build/release/rollbench."""
import os
import pathlib
import subprocess
import sys

sys.path[0] = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from analysis import safe_files  # noqa: E402

DOC = pathlib.Path(__file__).resolve().parent.parent / "docs" / "integrators.md"
BEGIN = "<!-- method table: written by scripts/method_table.py from `rollbench list --markdown`; do not edit -->"
END = "<!-- end of the method table -->"


def generated(rollbench):
    return subprocess.run([rollbench, "list", "--markdown"], check=True, capture_output=True, text=True).stdout


def split(text):
    """(before, block, after) of the doc around its markers; ValueError naming the marker that is missing."""
    if text.count(BEGIN) != 1 or text.count(END) != 1:
        raise ValueError(f"{DOC}: expected each marker once: {BEGIN!r}, {END!r}")
    head, rest = text.split(BEGIN + "\n", 1)
    block, tail = rest.split(END, 1)
    return head, block, tail


def main(argv):
    check = "--check" in argv
    args = [a for a in argv if a != "--check"]
    rollbench = args[0] if args else "build/release/rollbench"
    text = safe_files.read_text(DOC, "doc")
    head, block, tail = split(text)
    table = generated(rollbench)
    if check:
        if block == table:
            return 0
        old, new = block.splitlines(), table.splitlines()
        first = next((i for i, (a, b) in enumerate(zip(old, new)) if a != b), min(len(old), len(new)))
        print(f"{DOC}: the method table is not `rollbench list --markdown` (line {first + 1} of the table); run "
              "scripts/method_table.py", file=sys.stderr)
        return 1
    safe_files.write_file(DOC, head + BEGIN + "\n" + table + END + tail)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

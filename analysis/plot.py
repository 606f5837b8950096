#!/usr/bin/python3
"""Figures and summary.md from a rollbench report.

    analysis/plot.py REPORT.json --out DIR [--perf PERF.json]
                     [--trajectories DIR] [--scenes DIR]

Writes convergence-<scene>.png, work-precision-<scene>.png, drift-<scene>.png,
stability.png, scenes.png, ns-per-step.png (with --perf) and summary.md.
A figure whose data the report lacks is skipped with a message; the exit
status is 0 unless the report cannot be read (2).
"""
import argparse
import json
import os
import sys

if __package__ in (None, ""):
    # run as a script: import the analysis package from the repository root,
    # not from this folder (so no module here can shadow another)
    _root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    sys.path[0] = _root

from analysis import figures, figures_overview, style, summary  # noqa: E402
from analysis import report as rp  # noqa: E402

DEFAULT_SCENES = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "problems", "scenes")


def build_figures(report, perf=None, trajectories=None, scene_dir=DEFAULT_SCENES, messages=None):
    """{file name: Figure} for every figure the data allows; skipped ones go to messages."""
    messages = messages if messages is not None else []
    palette = style.Palette(rp.families(report))
    if perf is not None:
        # benchmarks may name methods the report did not run: they get the unknown-family colour
        known = rp.families(report)
        names = [e[1] for e in figures_overview.perf_entries(perf)]
        palette = style.Palette({**{n: known.get(n) for n in names}, **known})
    out = {}

    def attempt(name, make):
        try:
            out[name] = make()
        except figures.NothingToPlot as e:
            messages.append(f"skipped {name}: {e}")

    scenes = rp.scenes(report)
    if not scenes:
        messages.append("the report has no runs and no stability results: no per-scene figures")
    for scene in scenes:
        attempt(f"convergence-{scene}.png", lambda: figures.convergence(report, scene, palette))
        attempt(f"work-precision-{scene}.png", lambda: figures.work_precision(report, scene, palette))
        attempt(f"drift-{scene}.png", lambda: figures.drift(report, scene, palette))
    attempt("stability.png", lambda: figures_overview.stability(report, palette))
    attempt("scenes.png", lambda: figures_overview.scenes(report, scene_dir, trajectories, messages))
    if perf is not None:
        attempt("ns-per-step.png", lambda: figures_overview.ns_per_step(perf, palette))
    return out


def write_all(report, out_dir, perf=None, trajectories=None, scene_dir=DEFAULT_SCENES, log=print, figures_out=None):
    """Writes every figure and summary.md into out_dir; returns the paths written.

    figures_out, a dict, receives the Figures by file name (for tests).
    """
    os.makedirs(out_dir, exist_ok=True)
    messages = []
    written = []
    built = build_figures(report, perf, trajectories, scene_dir, messages)
    if figures_out is not None:
        figures_out.update(built)
    for name, fig in built.items():
        path = os.path.join(out_dir, name)
        try:
            # tight: the legends sit outside the axes
            fig.savefig(path, bbox_inches="tight")
        except (ValueError, RuntimeError, OverflowError) as e:
            # one figure that cannot be drawn must not cost the others
            messages.append(f"could not draw {name}: {e}")
            continue
        written.append(path)
    path = os.path.join(out_dir, "summary.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write(summary.summary_markdown(report))
    written.append(path)
    for m in messages:
        log(m)
    for p in written:
        log(f"wrote {p}")
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("report", help="a rollbench.report/1 JSON file")
    parser.add_argument("--out", required=True, help="folder for the figures and summary.md")
    parser.add_argument("--perf", help="Google Benchmark JSON (--benchmark_out) for ns-per-step.png")
    parser.add_argument("--trajectories", help="folder of <scene>.csv trajectories (rollbench trajectory)")
    parser.add_argument("--scenes", default=DEFAULT_SCENES, help="folder of scene JSON files (default: %(default)s)")
    args = parser.parse_args(argv)
    try:
        report = rp.load(args.report)
    except rp.ReportError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    perf = None
    if args.perf:
        try:
            with open(args.perf, encoding="utf-8") as f:
                perf = json.load(f)
            if not isinstance(perf, dict):
                raise ValueError("not a JSON object")
        except (OSError, ValueError) as e:
            print(f"error: cannot read the benchmark file '{args.perf}': {e}", file=sys.stderr)
            return 2
    write_all(report, args.out, perf, args.trajectories, args.scenes)
    return 0


if __name__ == "__main__":
    sys.exit(main())

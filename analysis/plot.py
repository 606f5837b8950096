#!/usr/bin/python3
"""Figures, summary.md and index.html from a rollbench report.

    analysis/plot.py REPORT.json --out DIR [--metric worst|contact|centre|omega|rotation] [--errors end|max]
                     [--perf PERF.json] [--trajectories DIR] [--ball DIR] [--scenes DIR]
                     [--rollbench PATH] [--scene-figures]

Writes answer.png (flat/Lie per scene where R feeds back: the first
screen's figure), per scene convergence-, work-precision-,
work-precision-best-, tolerance- and drift-<scene>.png (for a regime study only with
--scene-figures), regime-border.png and regime-<target>.png (analysis/regime.py) and
horizon-<scene>.png per scene of the horizon study and horizon-cost.png
(analysis/horizon_ladder.py); then stability.png, scenes.png,
ball-deforms.png (with --ball), ns-per-step.png (with --perf), summary.md,
index.html (the answer, its figure, the other figures with captions and the
summary) and all-methods.html (the every-method work-precision charts).
A figure whose data the report lacks is skipped with a message; the exit
status is 0 unless the input cannot be read (2).
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

from analysis import figures, figures_answer, figures_ball, figures_overview, figures_precision  # noqa: E402
from analysis import html, landscape  # noqa: E402
from analysis import answer, horizon, horizon_ladder, regime, style, summary  # noqa: E402
from analysis import report as rp  # noqa: E402
from analysis import safe_files  # noqa: E402

DEFAULT_SCENES = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "problems", "scenes")


class Options:
    """What the figures are drawn from beside the report."""

    def __init__(self, metric=rp.DEFAULT_METRIC, perf=None, trajectories=None, ball=None,
                 scene_dir=DEFAULT_SCENES, rollbench=landscape.DEFAULT_ROLLBENCH, scene_figures=None):
        self.metric, self.perf, self.trajectories, self.ball = metric, perf, trajectories, ball
        self.scene_dir, self.rollbench = scene_dir, rollbench
        # per-scene figures: None draws them unless the report is a regime study
        # (dozens of generated scenes: minutes of figures nobody looks at one by one)
        self.scene_figures = scene_figures


def build_figures(report, options=None, messages=None, log=None):
    """{file name: Figure} for every figure the data allows; skipped ones go to messages."""
    options = options or Options()
    messages = messages if messages is not None else []
    palette = style.Palette(rp.families(report))
    if options.perf is not None:
        # benchmarks may name methods the report did not run: they get the unknown-family colour
        known = rp.families(report)
        names = [e[1] for e in figures_overview.perf_entries(options.perf)]
        palette = style.Palette({**{n: known.get(n) for n in names}, **known})
    out = {}

    def attempt(name, make):
        try:
            out[name] = make()
        except figures.NothingToPlot as e:
            messages.append(f"skipped {name}: {e}")

    metric = options.metric
    # the first screen's figure, from the cells the answer sentences count
    attempt(answer.FIGURE, lambda: figures_answer.answer_figure(report, metric))
    scenes = rp.scenes(report)
    if not scenes:
        messages.append("the report has no runs and no stability results: no per-scene figures")
    per_scene = not (options.scene_figures is False or (options.scene_figures is None and regime.cells(report)))
    if not per_scene:
        messages.append(f"skipped the per-scene figures and scenes.png of {len(scenes)} scenes"
                        + (" (a regime study: --scene-figures draws them)" if regime.cells(report) else ""))
        scenes = []
    for i, scene in enumerate(scenes):
        if log:
            log(f"figures for {scene} ({i + 1} of {len(scenes)})")
        attempt(f"convergence-{scene}.png", lambda: figures.convergence(report, scene, palette))
        attempt(f"work-precision-{scene}.png",
                lambda: figures_precision.work_precision(report, scene, palette, metric))
        attempt(f"work-precision-best-{scene}.png",
                lambda: figures_precision.work_precision_best(report, scene, palette, metric))
        attempt(f"tolerance-{scene}.png", lambda: figures_precision.tolerance(report, scene, palette, metric))
        attempt(f"drift-{scene}.png", lambda: figures.drift(report, scene, palette))
    if regime.cells(report):  # the regime study's heat maps, regime-<target>.png
        results = regime.regime_results(report, metric)
        attempt(regime.BORDER_FIGURE, lambda: regime.border_figure(report, metric, results))
        for target in regime.TARGETS:
            attempt(regime.figure_name(target), lambda: regime.heat_map(report, target, metric, results))
    for scene in horizon.scenes(report):
        attempt(f"horizon-{scene}.png", lambda: horizon.figure(report, scene, palette))
    if horizon.scenes(report):
        attempt(horizon_ladder.COST_FIGURE, lambda: horizon_ladder.cost_figure(report, palette))
    attempt("stability.png", lambda: figures_overview.stability(report, palette))
    if per_scene:
        attempt("scenes.png", lambda: figures_overview.scenes(report, options.scene_dir, options.trajectories,
                                                              messages, options.rollbench))
    if options.ball is not None:
        attempt("ball-deforms.png", lambda: figures_ball.ball_deforms(options.ball))
    if options.perf is not None:
        attempt("ns-per-step.png", lambda: figures_overview.ns_per_step(options.perf, palette))
    return out


def write_all(report, out_dir, options=None, log=print, figures_out=None):
    """Writes every figure, summary.md and index.html into out_dir; returns the paths written.

    figures_out, a dict, receives the Figures by file name (for tests).
    """
    options = options or Options()
    # opened before the work, under the path rule (analysis/safe_files.py): every file goes through it
    with safe_files.OutputFolder(out_dir, create=True) as folder:
        messages = []
        written = []
        built = build_figures(report, options, messages, log)
        if figures_out is not None:
            figures_out.update(built)
        for name, fig in built.items():
            try:
                # tight: the legends sit outside the axes
                written.append(folder.write_figure(name, fig, bbox_inches="tight"))
            except safe_files.OutputFileError:
                raise
            except (ValueError, RuntimeError, OverflowError) as e:
                # one figure that cannot be drawn must not cost the others
                messages.append(f"could not draw {name}: {e}")
        text = summary.summary_markdown(report, options.metric)
        names = [os.path.basename(p) for p in written]
        pages = [("summary.md", text), ("index.html", html.index_html(names, text))]
        if any(html.all_methods(n) for n in names):
            pages.append((html.ALL_METHODS_PAGE, html.all_methods_html(names)))
        for name, content in pages:
            written.append(folder.write_text(name, content))
    for m in messages:
        log(m)
    for p in written:
        log(f"wrote {p}")
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("report", help=f"a {rp.SCHEMA} JSON file")
    parser.add_argument("--out", required=True, help="folder for the figures, summary.md and index.html")
    parser.add_argument("--metric", default=rp.DEFAULT_METRIC,
                        help="accuracy axis of the work-precision figures and cost tables: worst or one of the "
                             "report's error_components (default: %(default)s)")
    parser.add_argument("--errors", choices=sorted(rp.ERROR_KEYS), default="end",
                        help="errors at t_end (end) or the largest over the timed run's steps (max) "
                             "(default: %(default)s)")
    parser.add_argument("--perf", help="Google Benchmark JSON (--benchmark_out) for ns-per-step.png")
    parser.add_argument("--trajectories", help="folder of <scene>.csv trajectories (rollbench trajectory)")
    parser.add_argument("--ball", help="folder of euler.csv, rk4.csv, rkmk4.csv trajectories for ball-deforms.png")
    parser.add_argument("--scenes", default=DEFAULT_SCENES, help="folder of scene JSON files (default: %(default)s)")
    parser.add_argument("--scene-figures", action="store_true", default=None,
                        help="draw the per-scene figures of a regime study too (default: only its heat maps)")
    parser.add_argument("--rollbench", default=landscape.DEFAULT_ROLLBENCH,
                        help="the rollbench binary that evaluates the landscapes (default: %(default)s)")
    args = parser.parse_args(argv)
    rp.use_errors(args.errors)
    try:
        report = rp.load(args.report)
    except rp.ReportError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.metric not in rp.metrics(report):
        print(f"error: --metric {args.metric!r} is none of {', '.join(rp.metrics(report))} (worst and the report's "
              "error_components)", file=sys.stderr)
        return 2
    perf = None
    if args.perf:
        try:
            perf = json.loads(safe_files.read_text(args.perf, "benchmark file"))
            if not isinstance(perf, dict):
                raise ValueError("not a JSON object")
        except safe_files.InputFileError as e:
            print(f"error: {e}", file=sys.stderr)
            return 2
        except (ValueError, RecursionError) as e:
            print(f"error: cannot read the benchmark file {safe_files.shown(args.perf)}: {e}", file=sys.stderr)
            return 2
    try:
        write_all(report, args.out, Options(args.metric, perf, args.trajectories, args.ball, args.scenes,
                                            args.rollbench, args.scene_figures))
    except safe_files.OutputFileError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Every figure is written and not blank, and the per-scene figures have one
labelled line per integrator of the scene on every axes."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

from analysis import plot, style  # noqa: E402
from analysis import report as rp  # noqa: E402
from tests.analysis import synthetic as syn  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE_DIR = os.path.join(ROOT, "problems", "scenes")


def labelled_lines(ax):
    return [line for line in ax.get_lines() if not line.get_label().startswith("_")]


def expected_files(report, perf=True):
    names = {"stability.png", "scenes.png", "summary.md"} | ({"ns-per-step.png"} if perf else set())
    for scene in rp.scenes(report):
        names |= {f"convergence-{scene}.png", f"work-precision-{scene}.png", f"drift-{scene}.png"}
    return names


class FiguresOfSyntheticReport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.report = syn.make_report()
        cls.perf = syn.perf_json()
        cls.trajectories = os.path.join(cls.tmp.name, "trajectories")
        os.makedirs(cls.trajectories)
        syn.trajectory_csv(os.path.join(cls.trajectories, "valley-sideways.csv"))
        cls.out = os.path.join(cls.tmp.name, "out")
        cls.log, cls.figures = [], {}
        cls.written = plot.write_all(cls.report, cls.out, cls.perf, cls.trajectories, SCENE_DIR, cls.log.append,
                                     figures_out=cls.figures)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_figure_is_written_and_not_blank(self):
        self.assertEqual(set(os.listdir(self.out)), expected_files(self.report))
        # nothing skipped: the log holds only the files written
        self.assertEqual([m for m in self.log if not m.startswith("wrote ")], [])
        for name in sorted(os.listdir(self.out)):
            if not name.endswith(".png"):
                continue
            with self.subTest(figure=name):
                pixels = mpimg.imread(os.path.join(self.out, name))
                self.assertGreater(pixels.shape[0], 200)
                self.assertGreater(pixels.shape[1], 200)
                self.assertGreater(float(np.var(pixels[..., :3])), 1e-3)

    def test_convergence_has_a_line_per_fixed_step_integrator(self):
        for scene in syn.SCENES:
            fig = self.figures[f"convergence-{scene}.png"]
            axes = [ax for ax in fig.axes if ax.get_lines()]
            self.assertEqual(len(axes), 2)  # contact point and rotation
            for ax in axes:
                lines = labelled_lines(ax)
                self.assertEqual(len(lines), len(syn.FIXED))
                self.assertEqual({line.get_label().split()[0] for line in lines}, set(syn.FIXED))
                self.assertEqual(ax.get_xscale(), "log")
                self.assertEqual(ax.get_yscale(), "log")
                self.assertIn(scene, ax.get_title())

    def test_convergence_legend_shows_the_observed_orders(self):
        fig = self.figures["convergence-valley-sideways.png"]
        contact, rotation = [ax for ax in fig.axes if ax.get_lines()]
        labels = {line.get_label().split()[0]: line.get_label() for line in labelled_lines(rotation)}
        self.assertIn("p = 3.00", labels["rkmk4-seminar"])
        self.assertIn("p = 4.00", labels["rkmk4"])
        self.assertIn("[1 failed]", labels["euler"])

    def test_work_precision_has_a_line_per_integrator(self):
        for scene in syn.SCENES:
            fig = self.figures[f"work-precision-{scene}.png"]
            axes = [ax for ax in fig.axes if ax.get_lines()]
            self.assertEqual(len(axes), 2)  # wall time and rhs evaluations
            for ax in axes:
                lines = labelled_lines(ax)
                self.assertEqual(len(lines), len(syn.FIXED) + len(syn.ADAPTIVE))
                self.assertTrue(all(len(line.get_xdata()) > 0 for line in lines))

    def test_drift_draws_each_drift_run_and_each_integrator(self):
        fig = self.figures["drift-valley-sideways.png"]
        axes = [ax for ax in fig.axes if ax.get_lines()]
        self.assertEqual(len(axes), 4)
        drift = [d for d in self.report["stability"]["drift"] if d["scene"] == "valley-sideways"]
        for ax in axes[:2]:
            self.assertEqual(len(labelled_lines(ax)), len(drift))
            self.assertEqual(ax.get_xlabel(), "time t (s)")
        for ax in axes[2:]:
            self.assertEqual(len(labelled_lines(ax)), len(syn.FIXED) + len(syn.ADAPTIVE))
        # the plane has no drift runs: only the panels against cost
        self.assertEqual(len([ax for ax in self.figures["drift-plane.png"].axes if ax.get_lines()]), 2)

    def test_an_integrator_looks_the_same_in_every_figure(self):
        colours = {}
        for name, fig in self.figures.items():
            if not name.startswith(("convergence", "work-precision")):
                continue
            for ax in fig.axes:
                for line in labelled_lines(ax):
                    key = line.get_label().split()[0]
                    look = (tuple(np.round(matplotlib.colors.to_rgb(line.get_color()), 6)), line.get_marker(),
                            line.get_linestyle())
                    colours.setdefault(key, set()).add(look)
        self.assertTrue(all(len(v) == 1 for v in colours.values()), colours)

    def test_minimal_and_empty_reports_do_not_crash(self):
        with tempfile.TemporaryDirectory() as out:
            log = []
            plot.write_all(syn.subset(syn.minimal_report(), "plane", ("rk4", "rkmk4", "gsl-rkf45-adaptive")), out,
                           log=log.append)
            self.assertIn("stability.png", os.listdir(out))
            self.assertIn("convergence-plane.png", os.listdir(out))
        with tempfile.TemporaryDirectory() as out:
            log = []
            written = plot.write_all({"schema": rp.SCHEMA, "runs": []}, out, perf={"benchmarks": []},
                                     log=log.append)
            self.assertEqual([os.path.basename(p) for p in written], ["summary.md"])
            self.assertTrue(any(m.startswith("skipped stability.png") for m in log))
            self.assertTrue(any(m.startswith("skipped ns-per-step.png") for m in log))

    def test_a_report_where_every_run_failed_still_draws(self):
        report = syn.subset(syn.make_report(), "plane", ("rk4", "gsl-rkf45-adaptive"))
        del report["stability"]  # it has another scene
        for run in report["runs"]:
            run["status"] = "diverged"
            run["error"].update(contact=None, centre=None, omega=None, rotation=None)
        with tempfile.TemporaryDirectory() as out:
            log = []
            plot.write_all(report, out, log=log.append)
            self.assertEqual([m for m in log if not m.startswith("wrote ")], [])
            for name in ("convergence-plane.png", "work-precision-plane.png", "drift-plane.png", "stability.png"):
                self.assertIn(name, os.listdir(out))

    def test_command_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "report.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(syn.subset(syn.minimal_report(), "plane", ("euler", "rk4")), f)
            done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "plot.py"), path, "--out",
                                   os.path.join(tmp, "out")], capture_output=True, text=True, cwd=tmp)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertIn("summary.md", os.listdir(os.path.join(tmp, "out")))
            bad = os.path.join(tmp, "bad.json")
            with open(bad, "w", encoding="utf-8") as f:
                json.dump({"schema": rp.SCHEMA, "runs": [{"scene": "plane"}]}, f)
            done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "plot.py"), bad, "--out", tmp],
                                  capture_output=True, text=True, cwd=tmp)
            self.assertEqual(done.returncode, 2)
            self.assertIn("runs[0] has no key 'integrator'", done.stderr)


class Styles(unittest.TestCase):
    def test_families_have_distinct_hues(self):
        colours = {style.family_colour(f) for f in ("rk", "rkmk", "odeint", "gsl", "lie-adaptive", "projection",
                                                     "quaternion")}
        self.assertEqual(len(colours), 7)
        self.assertEqual(style.family_colour("some-new-family"), style.family_colour("some-new-family"))

    def test_members_of_a_family_differ_and_do_not_depend_on_order(self):
        families = {n: f for n, (f, *_rest) in syn.FIXED.items()}
        a = style.Palette(families)
        b = style.Palette(dict(reversed(list(families.items()))))
        looks = set()
        for name in families:
            self.assertEqual(a.style(name), b.style(name))
            looks.add((a.style(name)["color"], a.style(name)["marker"], a.style(name)["linestyle"]))
        self.assertEqual(len(looks), len(families))


class ReportValidation(unittest.TestCase):
    def test_missing_keys_are_named(self):
        with self.assertRaisesRegex(rp.ReportError, "missing key 'schema'"):
            rp.validate({"runs": []})
        with self.assertRaisesRegex(rp.ReportError, "this analysis reads"):
            rp.validate({"schema": "rollbench.report/2"})
        report = syn.make_report()
        del report["runs"][5]["status"]
        with self.assertRaisesRegex(rp.ReportError, r"runs\[5\] has no key 'status'"):
            rp.validate(report)
        report = syn.make_report()
        del report["stability"]["drift"][0]["t"]
        with self.assertRaisesRegex(rp.ReportError, r"stability.drift\[0\] has no key 't'"):
            rp.validate(report)


if __name__ == "__main__":
    unittest.main()

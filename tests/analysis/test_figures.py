"""Every figure is written and not blank, and the per-scene figures have one
labelled line per integrator of the scene on every axes."""
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

from analysis import figures, figures_ball, figures_overview, figures_precision, plot, style  # noqa: E402
from analysis import report as rp  # noqa: E402
from tests.analysis import synthetic as syn  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE_DIR = os.path.join(ROOT, "problems", "scenes")


def labelled_lines(ax):
    return [line for line in ax.get_lines() if not line.get_label().startswith("_")]


def expected_files(report, perf=True):
    names = {"answer.png", "stability.png", "scenes.png", "ball-deforms.png", "summary.md", "index.html",
             "all-methods.html"}
    names |= {"ns-per-step.png"} if perf else set()
    for scene in rp.scenes(report):
        names |= {f"convergence-{scene}.png", f"work-precision-{scene}.png", f"work-precision-best-{scene}.png",
                  f"tolerance-{scene}.png", f"drift-{scene}.png"}
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
        cls.ball = os.path.join(cls.tmp.name, "ball")
        os.makedirs(cls.ball)
        for name, growth in syn.BALL_GROWTH.items():
            syn.ball_csv(os.path.join(cls.ball, f"{name}.csv"), growth)
        cls.out = os.path.join(cls.tmp.name, "out")
        cls.log, cls.figures = [], {}
        options = plot.Options(perf=cls.perf, trajectories=cls.trajectories, ball=cls.ball, scene_dir=SCENE_DIR)
        cls.written = plot.write_all(cls.report, cls.out, options, cls.log.append, figures_out=cls.figures)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_figure_is_written_and_not_blank(self):
        self.assertEqual(set(os.listdir(self.out)), expected_files(self.report))
        # nothing skipped: the log holds only the files written
        self.assertEqual([m for m in self.log if not m.startswith(("wrote ", "figures for "))], [])
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
            self.assertEqual(len(axes), len(syn.COMPONENTS))  # a panel per error component of the report
            for ax in axes:
                lines = labelled_lines(ax)
                self.assertEqual(len(lines), len(syn.FIXED))
                self.assertEqual({line.get_label().split()[0] for line in lines}, set(syn.FIXED))
                self.assertEqual(ax.get_xscale(), "log")
                self.assertEqual(ax.get_yscale(), "log")
                self.assertIn(scene, ax.get_title())

    def test_convergence_legend_shows_the_observed_orders(self):
        fig = self.figures["convergence-valley-sideways.png"]
        panels = [ax for ax in fig.axes if ax.get_lines()]
        rotation = panels[syn.COMPONENTS.index("rotation")]
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

    def test_work_precision_says_its_metric(self):
        for name in ("work-precision-plane.png", "work-precision-best-plane.png"):
            axes = [ax for ax in self.figures[name].axes if ax.get_lines()]
            self.assertEqual(axes[0].get_ylabel(), rp.WORST_LABEL)
            self.assertTrue(all("worst error against" in ax.get_title() for ax in axes))
        fig = figures_precision.work_precision(self.report, "plane", style.Palette(rp.families(self.report)),
                                               "rotation")
        self.assertEqual(fig.axes[0].get_ylabel(), "rotation error (rad)")
        self.assertIn("rotation error against wall time", fig.axes[0].get_title())

    def test_best_of_each_family_has_one_line_per_family(self):
        families = {f for f, *_rest in list(syn.FIXED.values()) + list(syn.ADAPTIVE.values())}
        for scene in syn.SCENES:
            for ax in [ax for ax in self.figures[f"work-precision-best-{scene}.png"].axes if ax.get_lines()]:
                labels = [line.get_label() for line in labelled_lines(ax)]
                self.assertEqual(sorted(label.split(":")[0] for label in labels), sorted(families))

    def test_pareto_choice(self):
        # a beats b at every cost: a is the family's best; the front drops dominated points
        self.assertEqual(figures_precision.pareto_front([(1, 1e-2), (2, 1e-3), (3, 1e-2), (4, 1e-5)]), [0, 1, 3])
        runs = [rp.Run.of({"scene": "plane", "integrator": n, "adaptive": False, "status": "ok", "rhs_evals": c,
                           "error": {"worst": e}})
                for n, c, e in (("a", 10, 1e-3), ("a", 100, 1e-7), ("b", 20, 1e-3), ("b", 200, 1e-6))]
        pick = figures_precision.best_of_family(runs, ["b", "a"], lambda r: r.rhs_evals, "worst", 0.0)
        self.assertEqual(pick, "a")

    def test_tolerance_figure_shows_the_fitted_slopes(self):
        ax = self.figures["tolerance-plane.png"].axes[0]
        labels = [line.get_label() for line in labelled_lines(ax)]
        self.assertEqual(len(labels), len(syn.ADAPTIVE) + 1)
        self.assertIn("gsl-rkf45-adaptive: fitted slope 0.80", labels)
        self.assertIn("rkmk-f78-adaptive: fitted slope 1.00", labels)
        self.assertIn("error = tolerance (slope 1)", labels)

    def test_the_ball_deforms_as_the_trajectories_say(self):
        fig = self.figures["ball-deforms.png"]
        titles = [ax.get_title() for ax in fig.axes]
        self.assertEqual(len(titles), len(syn.BALL_GROWTH) * figures_ball.TIMES)
        for name, growth in syn.BALL_GROWTH.items():
            last = [t for t in titles if t.startswith(f"{name}, t = {syn.T_END:g} s")]
            self.assertEqual(len(last), 1, titles)
            self.assertIn(f"axes ratio {1 + growth * syn.T_END:.3f}", last[0])

    def test_ball_trajectories_are_found_by_method_and_step(self):
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("rk4-h0.08.csv", "rkmk4.csv", "rk45.csv", "notes.txt"):
                open(os.path.join(tmp, name), "w").close()
            found = figures_ball.trajectory_files(tmp, ("euler", "rk4", "rkmk4"))
        self.assertEqual([(m, label, os.path.basename(p)) for m, label, p in found],
                         [("rk4", "rk4, h = 0.08 s", "rk4-h0.08.csv"), ("rkmk4", "rkmk4", "rkmk4.csv")])

    def test_index_html_links_every_figure(self):
        with open(os.path.join(self.out, "index.html"), encoding="utf-8") as f:
            page = f.read()
        with open(os.path.join(self.out, "all-methods.html"), encoding="utf-8") as f:
            every = f.read()
        pngs = sorted(n for n in os.listdir(self.out) if n.endswith(".png"))
        # every figure once: the every-method charts on their own page, the rest on index.html
        shown = re.findall(r'<img src="([^"]+)"', page) + re.findall(r'<img src="([^"]+)"', every)
        self.assertEqual(sorted(shown), pngs)
        # the summary's tables are rendered, the escaped '|' restored inside its cell
        self.assertIn('<h2 id="same-tableau-flat-vs-lie-worst-error">Same tableau, flat vs Lie (worst error)</h2>',
                      page)
        self.assertIn("<td>gsl: step size underflow | h &lt; 1e-15</td>", page)
        # the findings open the page, before any figure; one table of contents; best of family first
        self.assertLess(page.index('<h2 id="findings">Findings</h2>'), page.index("<img "))
        self.assertEqual(page.count(">Contents</h2>"), 1)
        images = re.findall(r'<img src="([^"]+)"', page)
        self.assertTrue(images[1].startswith("work-precision-best-"), images)
        self.assertIn('<a href="#stability">Stability</a>', page)
        self.assertIn('id="stability"', page)

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
            if not name.startswith(("convergence", "work-precision-plane", "work-precision-valley")):
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
            self.assertIn("tolerance-plane.png", os.listdir(out))
            self.assertIn("stability.png", os.listdir(out))
            self.assertIn("convergence-plane.png", os.listdir(out))
        with tempfile.TemporaryDirectory() as out:
            log = []
            written = plot.write_all({"schema": rp.SCHEMA, "runs": []}, out, plot.Options(perf={"benchmarks": []}),
                                     log=log.append)
            self.assertEqual([os.path.basename(p) for p in written], ["summary.md", "index.html"])
            self.assertTrue(any(m.startswith("skipped stability.png") for m in log))
            self.assertTrue(any(m.startswith("skipped ns-per-step.png") for m in log))

    def test_a_report_where_every_run_failed_still_draws(self):
        report = syn.subset(syn.make_report(), "plane", ("rk4", "gsl-rkf45-adaptive"))
        del report["stability"]  # it has another scene
        for run in report["runs"]:
            run["status"] = "diverged"
            run["error"].update(contact=None, centre=None, omega=None, rotation=None, worst=None)
        with tempfile.TemporaryDirectory() as out:
            log = []
            plot.write_all(report, out, log=log.append)
            # plane only: no scene where R feeds back, so nothing for answer.png to answer
            self.assertEqual([m for m in log if not m.startswith(("wrote ", "figures for ", "skipped answer.png"))],
                             [])
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
            with open(bad, "w", encoding="utf-8") as f:
                json.dump({**syn.minimal_report(), "schema": "rollbench.report/1"}, f)
            done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "plot.py"), bad, "--out", tmp],
                                  capture_output=True, text=True, cwd=tmp)
            self.assertEqual(done.returncode, 2)
            self.assertIn("schema version 'rollbench.report/1' found, this analysis reads only "
                          "\"rollbench.report/2\"", done.stderr)
            done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "plot.py"), path, "--out", tmp,
                                   "--metric", "energy"], capture_output=True, text=True, cwd=tmp)
            self.assertEqual(done.returncode, 2)
            self.assertIn("--metric 'energy' is none of worst, contact, centre, omega, rotation (worst and the "
                          "report's error_components)", done.stderr)

    def test_a_scene_rollbench_refuses_is_left_out_with_its_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            with open(os.path.join(SCENE_DIR, "saddle.json"), encoding="utf-8") as f:
                scene = json.load(f)
            scene["landscape"] = "a*(x^2 - y^2) +* 1"
            with open(os.path.join(tmp, "plane.json"), "w", encoding="utf-8") as f:
                json.dump(scene, f)
            messages = []
            report = syn.subset(syn.make_report(), "plane", ("rk4",))
            del report["stability"]  # it names another scene
            with self.assertRaises(figures.NothingToPlot):
                figures_overview.scenes(report, tmp, None, messages)
            self.assertEqual(len(messages), 1, messages)
            self.assertRegex(messages[0], r"scenes.png: left out plane \(rollbench: 'landscape' column \d+: ")

    def test_a_scene_given_as_a_file_is_drawn_from_that_file(self):
        # the run was given my-valley.json (its name "plane"), not the shipped file:
        # scenes.png reads the file options.scenes records, not the scene folder
        with tempfile.TemporaryDirectory() as tmp:
            with open(os.path.join(SCENE_DIR, "saddle.json"), encoding="utf-8") as f:
                scene = json.load(f)
            scene["name"] = "plane"
            path = os.path.join(tmp, "my-valley.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(scene, f)
            report = syn.subset(syn.make_report(), "plane", ("rk4",))
            del report["stability"]
            report.setdefault("options", {})["scenes"] = [path]
            self.assertEqual(figures_overview.scene_files(report, SCENE_DIR), {"plane": path})
            empty = os.path.join(tmp, "empty")
            os.mkdir(empty)
            messages = []
            figures_overview.scenes(report, empty, None, messages)  # no scene folder holds it: drawn all the same
            self.assertEqual(messages, [])
            # a name given as a shipped scene is not a file: looked up in the folder
            report["options"]["scenes"] = ["plane"]
            self.assertEqual(figures_overview.scene_files(report, SCENE_DIR), {})


class Styles(unittest.TestCase):
    def test_families_have_distinct_hues(self):
        families = ("rk", "rkmk", "odeint", "gsl", "rkmk-adaptive", "projection", "quaternion")
        colours = {style.family_colour(f) for f in families}
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
        with self.assertRaisesRegex(rp.ReportError, "schema version 'rollbench.report/1' found, this analysis "
                                                    "reads only \"rollbench.report/2\""):
            rp.validate({"schema": "rollbench.report/1"})
        report = syn.make_report()
        del report["runs"][5]["status"]
        with self.assertRaisesRegex(rp.ReportError, r"runs\[5\] has no key 'status'"):
            rp.validate(report)
        report = syn.make_report()
        del report["stability"]["drift"][0]["t"]
        with self.assertRaisesRegex(rp.ReportError, r"stability.drift\[0\] has no key 't'"):
            rp.validate(report)
        report = syn.make_report()
        del report["error_components"]
        with self.assertRaisesRegex(rp.ReportError, "report: missing key 'error_components'"):
            rp.validate(report)
        report["error_components"] = [{"name": "contact", "unit": "m"}]
        with self.assertRaisesRegex(rp.ReportError, r"error_components\[0\] has no text key 'label'"):
            rp.validate(report)


if __name__ == "__main__":
    unittest.main()

"""The SciPy peer (analysis/peers/scipy_peer.py) end to end on a short scene:
the problem library through ctypes, the five solvers, `rollbench score
--peers` turning them into report runs, and the analysis drawing them.
CTest sets RB_PROBLEM_LIB and RB_ROLLBENCH to the build's."""
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np

from analysis import report as rp
from analysis.peers import problem_lib, scipy_peer

ROOT = problem_lib.ROOT
ROLLBENCH = os.environ.get("RB_ROLLBENCH") or os.path.join(ROOT, "build", "release", "rollbench")
TOLS = [1e-4, 1e-6, 1e-8]


class ProblemLibrary(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = problem_lib.load_library(problem_lib.DEFAULT_LIBRARY)

    def test_a_bad_scene_path_is_the_loaders_message_naming_the_file(self):
        with self.assertRaises(problem_lib.ProblemError) as e:
            problem_lib.Problem(self.lib, "/nonexistent/scene.json")
        self.assertIn("/nonexistent/scene.json", str(e.exception))

    def test_bad_json_names_the_file(self):
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            f.write('{"name": "x", "landscape": ')
        try:
            with self.assertRaises(problem_lib.ProblemError) as e:
                problem_lib.Problem(self.lib, f.name)
            self.assertTrue(str(e.exception).startswith(f"scene '{f.name}': invalid JSON at byte "), str(e.exception))
        finally:
            os.remove(f.name)

    def test_rhs_and_jacobian_agree_and_are_counted(self):
        with problem_lib.Problem(self.lib, "chaplygin-valley") as p:
            self.assertEqual(p.components[0], "r00")
            self.assertEqual(p.components[12:], ["x", "y"])
            y = p.y0 + 1e-3 * np.arange(14)
            J = p.jacobian(0.0, y)
            # the exact Jacobian against a central difference of the same rhs
            for j in (0, 9, 12):
                e = np.zeros(14)
                e[j] = 1e-6
                fd = (p.rhs(0.0, y + e) - p.rhs(0.0, y - e)) / 2e-6
                np.testing.assert_allclose(J[:, j], fd, rtol=1e-5, atol=1e-6)
            self.assertEqual(p.counts(), (6, 1))
            self.assertEqual(p.check(y), ("ok", ""))


class ScipyPeerScored(unittest.TestCase):
    """One run of the peer on valley-sideways to t = 1, scored once for all tests."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        out = cls.tmp.name
        scipy_peer.run_peers(problem_lib.DEFAULT_LIBRARY, ["valley-sideways"], list(scipy_peer.METHODS), TOLS,
                             1.0, 0.0, 1, 1000, out, progress=lambda _: None)
        cls.report_path = os.path.join(out, "report.json")
        cls.score = subprocess.run([ROLLBENCH, "score", "--peers", os.path.join(out, "peers.json"),
                                    "--out", cls.report_path], capture_output=True, text=True)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def setUp(self):
        self.assertEqual(self.score.returncode, 0, self.score.stderr)
        self.report = rp.load(self.report_path)
        self.runs = {(r["integrator"], r["rtol"]): r for r in self.report["runs"]}

    def test_every_solve_is_a_scored_run(self):
        self.assertEqual(len(self.runs), len(scipy_peer.METHODS) * len(TOLS))
        for (name, tol), r in self.runs.items():
            with self.subTest(name=name, tol=tol):
                self.assertEqual(r["status"], "ok", r["message"])
                self.assertEqual(r["family"], "scipy")
                self.assertGreater(r["error"]["worst"], 0.0)
                self.assertGreater(r["rhs_evals"], r["steps"])
                self.assertGreater(r["wall_s"]["median"], 0.0)
                self.assertEqual(r["timed_outputs"], 4)  # 0.25, 0.5, 0.75, 1
                # LSODA evaluates it only once it switches to BDF (stiff)
                if r["peer"]["method"] != "LSODA":
                    self.assertEqual(r["jacobian_evals"] > 0, r["needs_jacobian"])
                self.assertGreater(r["peer"]["rhs_cost_s"], 0.0)

    def test_rk45_error_falls_with_the_tolerance_at_about_its_order(self):
        errors = [self.runs[("scipy-rk45", t)]["error"]["worst"] for t in TOLS]
        self.assertLess(errors[1], errors[0] / 10)
        self.assertLess(errors[2], errors[1] / 10)
        fit = next(f for f in self.report["tolerance_fits"] if f["integrator"] == "scipy-rk45")
        self.assertGreater(fit["slope"], 0.7)
        # error ~ mean step^5: order 5 within 1.5 over these three points
        self.assertLess(abs(fit["step_order"]["slope"] - 5.0), 1.5, fit["step_order"])

    def test_dop853_is_the_cheaper_at_the_tightest_tolerance(self):
        tight = TOLS[-1]
        self.assertLess(self.runs[("scipy-dop853", tight)]["rhs_evals"], self.runs[("scipy-rk45", tight)]["rhs_evals"])

    def test_the_work_precision_figure_draws_the_scipy_methods(self):
        from analysis import figures_precision
        from analysis.style import Palette
        palette = Palette({r["integrator"]: r["family"] for r in self.report["runs"]})
        fig = figures_precision.work_precision(self.report, "valley-sideways", palette)
        labels = [line.get_label() for line in fig.axes[0].get_lines()]
        for m in scipy_peer.METHODS.values():
            self.assertIn(f"{m[0]} (adaptive)", labels)

    def test_the_summary_gives_declared_and_observed_orders(self):
        from analysis import summary
        text = "\n".join(summary.tolerance_section(self.report))
        fit = next(f for f in self.report["tolerance_fits"] if f["integrator"] == "scipy-rk45")
        self.assertIn(f"| valley-sideways | scipy-rk45 | 5(4) | {fit['step_order']['slope']:.2f} ± ", text)
        self.assertIn("| scipy-dop853 | 8(5,3) |", text)

    def test_a_report_of_other_end_times_is_refused(self):
        other = os.path.join(self.tmp.name, "other.json")
        with open(self.report_path) as f:
            report = json.load(f)
        report["references"][0]["t_end"] = 2.0
        with open(other, "w") as f:
            json.dump(report, f)
        r = subprocess.run([ROLLBENCH, "score", "--peers", os.path.join(self.tmp.name, "peers.json"), "--into", other,
                            "--out", os.path.join(self.tmp.name, "x.json")], capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("to t_end = 1", r.stderr)


class ScipyPeerPaths(unittest.TestCase):
    """Paths that are not UTF-8 (bytes as typed): a message and exit 2 where the peer file cannot hold one, a run
    where it need not."""

    def peer(self, *args, cwd=ROOT):
        return subprocess.run([b"/usr/bin/python3", b"-m", b"analysis.peers.scipy_peer", b"--library",
                               os.fsencode(problem_lib.DEFAULT_LIBRARY), b"--methods", b"RK45", b"--tol", b"1e-3",
                               b"--t-end", b"0.5", b"--repeats", b"1", b"--rhs-calls", b"10", *args],
                              capture_output=True, cwd=cwd)

    def test_a_scene_path_that_is_not_utf8_is_refused_naming_it(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.fsencode(tmp) + b"/\xff\x1b.json"
            r = self.peer(b"--scene", scene, b"--out", os.fsencode(tmp))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr.decode(), f"scipy_peer: --scene '{tmp}/\\xff\\x1b.json' is not UTF-8; the peer "
                                            "file records it as JSON text, so name it by a UTF-8 path\n")

    def test_an_output_folder_that_is_not_utf8_is_written_and_shown_escaped(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.fsencode(tmp) + b"/\xff-out"
            r = self.peer(b"--scene", b"plane", b"--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(r.stdout.decode(), f"peer file written to '{tmp}/\\xff-out/peers.json'\n")
            self.assertTrue(os.path.isfile(out + b"/peers.json"))
            self.assertEqual(os.listdir(out + b"/trajectories"), [b"plane-scipy-rk45-1e-03.csv"])


if __name__ == "__main__":
    unittest.main()

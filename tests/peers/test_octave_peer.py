"""The Octave peer (analysis/peers/octave_peer.py) end to end on a short scene:
the oct-file built with mkoctfile, ode45, ode23 and ode15s calling the problem
library, `rollbench score --peers` turning the solves into report runs, and the
analysis drawing them. CTest sets RB_PROBLEM_LIB and RB_ROLLBENCH to the build's."""
import json
import os
import subprocess
import tempfile
import unittest
from unittest import mock

from analysis import report as rp
from analysis.peers import octave_peer, problem_lib

ROOT = problem_lib.ROOT
ROLLBENCH = os.environ.get("RB_ROLLBENCH") or os.path.join(ROOT, "build", "release", "rollbench")
TOLS = [1e-4, 1e-6, 1e-8]


class OctavePeerScored(unittest.TestCase):
    """One run of the peer on valley-sideways to t = 1, and ode15s at 1e-10 where IDA gives up."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        out = cls.tmp.name
        octave_peer.run_peers(problem_lib.DEFAULT_LIBRARY, ["valley-sideways"], list(octave_peer.METHODS), TOLS,
                              1.0, 0.0, 1, 200, out, progress=lambda _: None)
        cls.report_path = os.path.join(out, "report.json")
        cls.score = subprocess.run([ROLLBENCH, "score", "--peers", os.path.join(out, "peers.json"),
                                    "--out", cls.report_path], capture_output=True, text=True)
        failing = os.path.join(out, "failing")
        octave_peer.run_peers(problem_lib.DEFAULT_LIBRARY, ["valley-sideways"], ["ode15s"], [1e-10], 1.0, 0.0, 1,
                              10, failing, progress=lambda _: None)
        cls.failing_report = os.path.join(failing, "report.json")
        cls.failing_score = subprocess.run([ROLLBENCH, "score", "--peers", os.path.join(failing, "peers.json"),
                                            "--out", cls.failing_report], capture_output=True, text=True)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def setUp(self):
        self.assertEqual(self.score.returncode, 0, self.score.stderr)
        self.report = rp.load(self.report_path)
        self.runs = {(r["integrator"], r["rtol"]): r for r in self.report["runs"]}

    def test_every_solve_is_a_scored_run(self):
        self.assertEqual(len(self.runs), len(octave_peer.METHODS) * len(TOLS))
        for (name, tol), r in self.runs.items():
            with self.subTest(name=name, tol=tol):
                self.assertEqual(r["status"], "ok", r["message"])
                self.assertEqual(r["family"], "octave")
                self.assertGreater(r["error"]["worst"], 0.0)
                self.assertGreater(r["rhs_evals"], r["steps"])
                self.assertGreater(r["steps"], 0)
                self.assertGreater(r["wall_s"]["median"], 0.0)
                self.assertEqual(r["timed_outputs"], 4)  # 0.25, 0.5, 0.75, 1
                self.assertEqual(r["jacobian_evals"] > 0, r["needs_jacobian"])
                self.assertGreater(r["peer"]["rhs_cost_s"], 0.0)

    def test_the_explicit_solvers_steps_are_the_timed_solves(self):
        # ode45 and ode23 step the same with and without output times; IDA stops at each one
        for (name, tol), r in self.runs.items():
            with self.subTest(name=name, tol=tol):
                source = r["peer"]["options"]["steps_source"]
                if name == "octave-ode15s":
                    self.assertNotEqual(source, "timed solve")
                else:
                    self.assertEqual(source, "timed solve")

    def test_ode45_error_falls_with_the_tolerance_at_about_its_order(self):
        errors = [self.runs[("octave-ode45", t)]["error"]["worst"] for t in TOLS]
        self.assertLess(errors[1], errors[0] / 10)
        self.assertLess(errors[2], errors[1] / 10)
        fit = next(f for f in self.report["tolerance_fits"] if f["integrator"] == "octave-ode45")
        self.assertLess(abs(fit["step_order"]["slope"] - 5.0), 1.5, fit["step_order"])

    def test_ode45_is_cheaper_than_ode23_at_the_tightest_tolerance(self):
        tight = TOLS[-1]
        self.assertLess(self.runs[("octave-ode45", tight)]["rhs_evals"],
                        self.runs[("octave-ode23", tight)]["rhs_evals"] / 3)

    def test_a_solver_that_gives_up_is_a_failed_run_with_octaves_message(self):
        self.assertEqual(self.failing_score.returncode, 0, self.failing_score.stderr)
        (run,) = rp.load(self.failing_report)["runs"]
        self.assertEqual(run["integrator"], "octave-ode15s")
        self.assertEqual(run["status"], "error")
        self.assertEqual(run["message"], "ode15s: IDASolve failed")

    def test_the_work_precision_figure_draws_the_octave_methods(self):
        from analysis import figures_precision
        from analysis.style import FAMILY_COLOURS, Palette
        palette = Palette({r["integrator"]: r["family"] for r in self.report["runs"]})
        fig = figures_precision.work_precision(self.report, "valley-sideways", palette)
        lines = {line.get_label(): line for line in fig.axes[0].get_lines()}
        for m in octave_peer.METHODS.values():
            self.assertIn(f"{m[0]} (adaptive)", lines)
        self.assertEqual(palette.family("octave-ode45"), "octave")
        self.assertIn("octave", FAMILY_COLOURS)


class OctavePeerRunsNothingPlanted(unittest.TestCase):
    """One run of the command line from a working folder with code planted in it (solve_peers.m, .octaverc,
    ode45.m, each of which would write a marker): Octave runs in a private folder, so none of it runs. And the
    oct-file built under a $TMPDIR whose name holds a shell command: mkoctfile gets no text of it."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        base = cls.tmp.name
        cls.markers = [os.path.join(base, f"MARKER-{name}") for name in ("solve_peers", "octaverc", "ode45")]
        cls.planted = os.path.join(base, "planted")
        os.mkdir(cls.planted)
        plants = {"solve_peers.m": "function solve_peers(varargin)\n  fclose(fopen('{}', 'w'));\nend\n",
                  ".octaverc": "fclose(fopen('{}', 'w'));\n",
                  "ode45.m": "function varargout = ode45(varargin)\n  fclose(fopen('{}', 'w'));\nend\n"}
        for (name, code), marker in zip(plants.items(), cls.markers):
            with open(os.path.join(cls.planted, name), "w") as f:
                f.write(code.format(marker))
        # a scene file named relative to the caller's working folder: Octave, run elsewhere, gets its absolute path
        with open(os.path.join(ROOT, "problems", "scenes", "valley-sideways.json")) as f:
            scene = f.read()
        with open(os.path.join(cls.planted, "my-scene.json"), "w") as f:
            f.write(scene)
        cls.out = os.path.join(base, "out")
        cls.done = subprocess.run(["/usr/bin/python3", "-m", "analysis.peers.octave_peer", "--library",
                                   problem_lib.DEFAULT_LIBRARY, "--scene", "my-scene.json", "--methods", "ode45",
                                   "--tol", "1e-4", "--t-end", "0.5", "--repeats", "1", "--rhs-calls", "10",
                                   "--out", cls.out], capture_output=True, text=True, cwd=cls.planted,
                                  env=dict(os.environ, PYTHONPATH=ROOT))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_peer_runs_and_writes_its_file(self):
        self.assertEqual(self.done.returncode, 0, self.done.stderr)
        with open(os.path.join(self.out, "peers.json")) as f:
            (run,) = json.load(f)["runs"]
        self.assertEqual((run["integrator"], run["status"], run["scene"]), ("octave-ode45", "ok", "my-scene.json"))

    def test_code_planted_in_the_working_folder_never_runs(self):
        self.assertEqual([m for m in self.markers if os.path.exists(m)], [])

    def test_a_command_in_tmpdir_never_runs(self):
        with tempfile.TemporaryDirectory() as base:
            pwned = os.path.join(base, "PWNED")
            # folders named so that a shell reading "$TMPDIR/..." runs `touch BASE/PWNED`
            hostile = os.path.join(base, f"X;touch {pwned};Y")
            os.makedirs(hostile)
            with mock.patch.dict(os.environ, TMPDIR=hostile):
                work = tempfile.mkdtemp(dir=hostile)  # as run_peers' private folder under this TMPDIR
                try:
                    built = octave_peer.build_oct_file(work)
                except octave_peer.OctaveError as e:
                    built = str(e)
            self.assertFalse(os.path.exists(pwned))
            self.assertEqual(built, os.path.join(work, "rb_problem.oct"))
            self.assertTrue(os.path.isfile(built))


class OctavePeerInput(unittest.TestCase):
    def test_a_bad_scene_exits_2_naming_the_file(self):
        with tempfile.TemporaryDirectory() as out:
            r = subprocess.run(["/usr/bin/python3", "-m", "analysis.peers.octave_peer", "--library",
                                problem_lib.DEFAULT_LIBRARY, "--scene", "/nonexistent/scene.json", "--out", out],
                               capture_output=True, text=True, cwd=ROOT)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertTrue(r.stderr.startswith("octave_peer: "), r.stderr)
        self.assertIn("/nonexistent/scene.json", r.stderr)

    def test_an_unknown_method_is_refused(self):
        with tempfile.TemporaryDirectory() as out:
            r = subprocess.run(["/usr/bin/python3", "-m", "analysis.peers.octave_peer", "--scene", "plane",
                                "--methods", "ode113", "--out", out], capture_output=True, text=True, cwd=ROOT)
        self.assertEqual(r.returncode, 2)
        self.assertIn("unknown method 'ode113'; Octave's are ode45, ode23, ode15s", r.stderr)

    def test_the_oct_file_refuses_a_state_of_the_wrong_size(self):
        with tempfile.TemporaryDirectory() as work:
            oct_dir = os.path.dirname(octave_peer.build_oct_file(work))
            code = (f"addpath('{oct_dir}'); rb_problem('load', '{problem_lib.DEFAULT_LIBRARY}');"
                    "[id, n, T, y0] = rb_problem('open', 'plane', 0);"
                    "try, rb_problem('rhs', id, 0, [1 2]); catch e, disp(e.message); end;"
                    "try, rb_problem('rhs', 99, 0, y0); catch e, disp(e.message); end")
            r = subprocess.run(["octave-cli", "--no-gui", "--norc", "--eval", code], capture_output=True, text=True)
        self.assertIn("rb_problem: a state has 14 entries, not 2\nrb_problem: no open problem 99\n", r.stdout)


if __name__ == "__main__":
    unittest.main()

"""Hostile reports against every command that reads one (issue 57, item 7): plot.py, compare.py (either side),
results.py and scripts/same-results.py exit 2 with one line naming the file and the key, never a traceback, and
write nothing; each report is a small valid one with one thing broken. A FIFO and /dev/zero are refused at once
(each command runs under a timeout, so a regression fails instead of hanging), a file over the limit before a byte
is read (sparse). A report that is only extreme (an error of 1e308) is valid: it is drawn, not refused."""
import json
import os
import stat
import subprocess
import sys
import tempfile
import unittest

from analysis import compare, json_limits, landscape, safe_files
from analysis import report as rp
from tests.analysis import synthetic as syn

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TIMEOUT_S = 20     # a refusal takes a second: a FIFO or /dev/zero that is read would hang or grow until then
DRAW_TIMEOUT_S = 300  # plot.py drawing a small report, on a loaded machine
TMP = None  # the module's folder, made once


def setUpModule():
    global TMP
    TMP = tempfile.TemporaryDirectory(prefix="rb-hostile-")


def tearDownModule():
    TMP.cleanup()


def small_report():
    """One scene, two fixed-step methods at two steps and one adaptive method at two tolerances."""
    report = syn.subset(syn.make_report(), "valley-sideways", ["rk4", "rkmk4", "odeint-dopri5-adaptive"])
    report["runs"] = [r for r in report["runs"] if r["h"] in (None, syn.HS[0], syn.HS[2])
                      and r["rtol"] in (None, syn.TOLS[0], syn.TOLS[2])]
    report["orders"] = [o for o in report["orders"] if o["scene"] == "valley-sideways"
                        and o["integrator"] in ("rk4", "rkmk4")]
    report["tolerance_fits"] = [f for f in report["tolerance_fits"] if f["scene"] == "valley-sideways"
                                and f["integrator"] == "odeint-dopri5-adaptive"]
    del report["stability"]
    return report


def write(name, content):
    path = os.path.join(TMP.name, name)
    with open(path, "wb") as f:
        f.write(content if isinstance(content, bytes) else json.dumps(content).encode("utf-8"))
    return path


def broken(name, change):
    """A file holding the small report with change(report) applied."""
    report = small_report()
    change(report)
    return write(name, report)


def run(*args, timeout=TIMEOUT_S):
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, timeout=timeout, cwd=TMP.name,
                          stdin=subprocess.DEVNULL)


def plot(path, timeout=TIMEOUT_S):
    out = os.path.join(TMP.name, "plots-" + os.path.basename(path))
    return run(os.path.join(ROOT, "analysis", "plot.py"), path, "--out", out, timeout=timeout), out


class HostileReports(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.good = write("good.json", small_report())

    def refused(self, done, *parts):
        """Exit status 2, one line on standard error holding each part, no traceback, nothing on standard output."""
        self.assertEqual(done.returncode, 2, done.stdout + done.stderr)
        self.assertNotIn("Traceback", done.stderr)
        self.assertEqual(done.stderr.count("\n"), 1, done.stderr)
        for part in parts:
            self.assertIn(part, done.stderr)
        self.assertEqual(done.stdout, "")

    def refused_by_plot(self, path, *parts):
        done, out = plot(path)
        self.refused(done, *parts)
        self.assertFalse(os.path.exists(out), "plot.py made its output folder for a report it refuses")

    def test_a_key_of_the_wrong_type_is_named_with_its_path(self):
        cases = {
            "number-as-text.json": (lambda r: r["runs"][1]["error"].__setitem__("worst", "1e-3"),
                                    "runs[1].error.worst is a string ('1e-3'), expected a number >= 0 or null"),
            "float-error.json": (lambda r: r["runs"][0].__setitem__("error", 1.5),
                                 "runs[0].error is a number (1.5), expected an object"),
            "integer-integrator.json": (lambda r: r["runs"][3].__setitem__("integrator", 7),
                                        "runs[3].integrator is a number (7), expected an integrator name"),
            "list-of-null.json": (lambda r: r["orders"].__setitem__(0, {**r["orders"][0], "observed": [None]}),
                                  "orders[0].observed is a list of 1, expected an object"),
            "true-as-order.json": (lambda r: r["runs"][0].__setitem__("declared_order", True),
                                   "runs[0].declared_order is true, expected a whole number from 0 to 100 or null"),
            "negative-time.json": (lambda r: r["runs"][2]["wall_s"].__setitem__("median", -1.0),
                                   "runs[2].wall_s.median is a number (-1.0), expected a number >= 0 or null"),
            "lone-surrogate.json": (lambda r: r["runs"][0].__setitem__("message", "\ud800"),
                                    "runs[0].message holds a \\u escape that is no character"),
        }
        for name, (change, message) in cases.items():
            with self.subTest(name):
                path = broken(name, change)
                self.refused_by_plot(path, f"error: {path}: {message}")

    def test_a_scene_name_that_is_not_a_file_name_is_refused(self):
        def slash(report):
            for entry in report["runs"] + report["references"] + report["orders"] + report["tolerance_fits"]:
                entry["scene"] = "../escape/valley"
        path = broken("scene-with-slash.json", slash)
        self.refused_by_plot(path, "references[0].scene is '../escape/valley', not a scene name (1 to 64 letters, "
                                   "digits, '-', '_' or '.', not starting with '.')")
        self.assertFalse(os.path.exists(os.path.join(TMP.name, "escape")))

    def test_json_past_its_limits_is_refused_before_it_is_parsed(self):
        good = json.dumps(small_report())
        cases = {
            "deep.json": (b"[" * 100000 + b"]" * 100000, "nests deeper than 64 levels (at byte 65)"),
            "deep-inside.json": (('{"schema": "rollbench.report/2", "extra": ' + "[" * 70 + "]" * 70 + "}").encode(),
                                 "nests deeper than 64 levels (at byte 106)"),
            "not-utf8.json": (good.replace("valley-sideways", "valley\udcff", 1).encode("utf-8", "surrogateescape"),
                              "is not UTF-8 (byte 0xff at offset"),
            "nan.json": (good.replace("null", "NaN", 1).encode(), "holds NaN, which is not JSON"),
            "overflow.json": (good.replace('"worst": ', '"worst": 1e400, "x": ', 1).encode(),
                              "holds a number out of range (1e400)"),
            "long-integer.json": (good.replace('"steps": ', '"steps": ' + "9" * 5000 + ', "x": ', 1).encode(),
                                  "holds a number out of range (9999"),
        }
        for name, (content, message) in cases.items():
            with self.subTest(name):
                path = write(name, content)
                self.refused_by_plot(path, f"'{path}' {message}")

    def test_a_fifo_a_device_and_a_huge_file_are_refused_at_once(self):
        fifo = os.path.join(TMP.name, "fifo.json")
        os.mkfifo(fifo)
        huge = os.path.join(TMP.name, "huge.json")
        with open(huge, "wb") as f:
            f.truncate(safe_files.REPORT_LIMIT + 1)  # sparse: nothing is written, and nothing must be read
        for path, message in ((fifo, "is a FIFO; inputs are read only from regular files"),
                              ("/dev/zero", "is a character device; inputs are read only from regular files"),
                              (huge, "is 1.07 GB; a report is at most 1 GiB")):
            with self.subTest(path):
                self.assertTrue(os.path.exists(path))
                self.refused_by_plot(path, f"error: '{path}' {message}")
        self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))

    def test_every_command_that_reads_a_report_refuses_the_same_way(self):
        bad = broken("every-command.json", lambda r: r["runs"][3].__setitem__("integrator", 7))
        message = f"{bad}: runs[3].integrator is a number (7), expected an integrator name"
        deep = write("every-command-deep.json", b"[" * 100000)
        page = os.path.join(TMP.name, "page.md")
        for path, text in ((bad, message), (deep, f"'{deep}' nests deeper than 64 levels")):
            commands = {"compare.py A": [os.path.join(ROOT, "analysis", "compare.py"), path, self.good],
                        "compare.py B": [os.path.join(ROOT, "analysis", "compare.py"), self.good, path],
                        "results.py": [os.path.join(ROOT, "analysis", "results.py"), path, "--out", page,
                                       "--title", "t", "--command", "c"],
                        "same-results.py": [os.path.join(ROOT, "scripts", "same-results.py"), "--reports", path,
                                            self.good]}
            for what, args in commands.items():
                with self.subTest(what, report=os.path.basename(path)):
                    self.refused(run(*args), text)
        self.assertFalse(os.path.exists(page))

    def test_an_extreme_but_valid_report_is_drawn(self):
        def extreme(report):
            run = report["runs"][0]
            for key in ("error", "error_max"):
                run[key]["contact"] = run[key]["worst"] = 1e308
            report["references"][1]["error"] = 1e308
            report["runs"][1]["drift"]["energy"] = 1e308
        path = broken("extreme.json", extreme)
        done, out = plot(path, timeout=DRAW_TIMEOUT_S)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertNotIn("Traceback", done.stderr)
        self.assertNotIn("could not draw", done.stdout)
        for name in ("convergence-valley-sideways.png", "work-precision-valley-sideways.png",
                     "drift-valley-sideways.png", "summary.md"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        done = run(os.path.join(ROOT, "analysis", "compare.py"), self.good, path, timeout=DRAW_TIMEOUT_S)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("error.worst", done.stdout)

    def test_the_keys_rollbench_writes_pass(self):
        # every key rollbench writes, in the types it writes them (docs/formats.md's examples)
        report = small_report()
        run = report["runs"][0]
        run.update({"index": 0, "needs_jacobian": False, "controller": "constant", "validity_checks": 10,
                    "newton": None, "timed_outputs": 1, "error_max_run": {"same_steps": True, "steps": 5000},
                    "error_grid": None, "scd": 8.0, "reversibility": {"status": "ok", "contact": 4.8e-9,
                                                                      "rotation": 2.4e-8, "momentum": 8.2e-11,
                                                                      "worst": 2.4e-8},
                    "final": {"t": 5.0, "contact": [0, 0], "centre": [0, 0, 0.1], "omega": [0, 0, 0],
                              "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}})
        run["error"]["points"] = 1
        report["references"][0].update({"component_errors": {"contact": 1e-14, "centre": None},
                                        "exact_rotation": True, "t_end": 2.0, "omega_scale": 3.0, "message": ""})
        text = json.dumps(report)
        self.assertEqual(rp.validate(json_limits.parse(text)), json.loads(text))


class RealReports(unittest.TestCase):
    """Reports rollbench writes pass every check: a sweep with its orders, tolerance fits, stability study and a
    horizon study with first integrals, and a regime study. Needs the built rollbench (CTest runs this after the
    build); a missing binary fails, it is never skipped."""

    SWEEPS = {
        "sweep.json": ["--preset", "default", "--scenes", "chaplygin-valley", "--integrators",
                       "rk4,rkmk4,odeint-dopri5-adaptive", "--h", "2^-4..2^-5", "--tol", "1e-4,1e-6", "--t-end", "1",
                       "--repeats", "1", "--horizon-steps", "1e3", "--horizon-scenes", "chaplygin-plane",
                       "--horizon-integrators", "rk4,rkmk4"],
        "regime.json": ["--preset", "regime", "--regime", "inertia=1,3;spin=5;roughness=0;t_end=1;bowl=0.5;speed=0.5;"
                        "held_out=none", "--integrators", "rk4,rkmk4", "--repeats", "1"],
    }

    def test_reports_of_rollbench_run_load(self):
        if not os.access(landscape.DEFAULT_ROLLBENCH, os.X_OK):
            raise AssertionError(f"no rollbench at {landscape.DEFAULT_ROLLBENCH}: build it first (cmake --build "
                                 "build/release --target rollbench) or set RB_ROLLBENCH")
        for name, args in self.SWEEPS.items():
            with self.subTest(name):
                path = os.path.join(TMP.name, name)
                done = subprocess.run([landscape.DEFAULT_ROLLBENCH, "run", *args, "--out", path], capture_output=True,
                                      text=True, timeout=DRAW_TIMEOUT_S)
                self.assertEqual(done.returncode, 0, done.stderr)
                report = rp.load(path)
                self.assertTrue(rp.runs(report))
                if name == "sweep.json":
                    self.assertTrue(rp.stable_steps(report) and rp.drift_runs(report))
                    self.assertTrue(any(r.get("invariants") for r in report["horizon"]["runs"]))
                else:
                    self.assertEqual(len(report["regime"]["cells"]), 2)
                done = run(os.path.join(ROOT, "analysis", "compare.py"), path, path, timeout=DRAW_TIMEOUT_S)
                self.assertEqual(done.returncode, 0, done.stderr)


class UnlikeReports(unittest.TestCase):
    """compare.py refuses two reports of other scenes, or with no run in both (issue 56, item 4)."""

    def test_other_scenes_are_refused_naming_them(self):
        a = syn.subset(syn.make_report(), "valley-sideways", ["rk4"])
        b = syn.subset(syn.make_report(), "plane", ["rk4"])
        with self.assertRaises(compare.Mismatch) as caught:
            compare.check_comparable(a, b, "a.json", "b.json")
        self.assertEqual(str(caught.exception), "the reports do not measure the same runs: their runs are of "
                         "other scenes (only in a.json: valley-sideways; only in b.json: plane)")
        pa, pb = write("scene-a.json", a), write("scene-b.json", b)
        done = run(os.path.join(ROOT, "analysis", "compare.py"), pa, pb)
        self.assertEqual(done.returncode, 2)
        self.assertEqual(done.stdout, "")
        self.assertEqual(done.stderr, f"error: the reports do not measure the same runs: their runs are of other "
                         f"scenes (only in {pa}: valley-sideways; only in {pb}: plane)\n")

    def test_no_run_in_both_is_refused(self):
        a = syn.subset(syn.make_report(), "plane", ["rk4"])
        b = syn.subset(syn.make_report(), "plane", ["rkmk4"])
        with self.assertRaises(compare.Mismatch) as caught:
            compare.check_comparable(a, b)
        self.assertEqual(str(caught.exception), "the reports do not measure the same runs: no run (scene, "
                         "integrator and step or tolerance) is in both")
        c = syn.subset(syn.make_report(), "plane", ["rk4", "rkmk4"])
        compare.check_comparable(a, c)  # a run in both: compared, the others listed as only in one


if __name__ == "__main__":
    unittest.main()

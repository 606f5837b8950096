"""scripts/same-results.py: one build against itself is the same run for run; a build whose CSVs, exit statuses
or registry differ is caught and named; two reports that differ only in timings are the same, and one value moved
by a bit is named by its path. Needs the built rollbench (RB_ROLLBENCH, set by CTest)."""
import json
import os
import stat
import subprocess
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "same-results.py")
ROLLBENCH = os.environ.get("RB_ROLLBENCH") or os.path.join(ROOT, "build", "release", "rollbench")
SMALL = ["--methods", "^(rk4|rkmk4|rk-bs32-adaptive)$", "--scenes", "plane,saddle", "--t-end", "0.3"]


def same_results(*args):
    return subprocess.run(["/usr/bin/python3", SCRIPT, *args], capture_output=True, text=True, timeout=600)


class Binaries(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not os.access(ROLLBENCH, os.X_OK):
            raise AssertionError(f"no rollbench at {ROLLBENCH}: build it first or set RB_ROLLBENCH")
        cls.tmp = tempfile.TemporaryDirectory()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def wrapper(self, name, body):
        """A stand-in for a changed build: rollbench run through a shell script."""
        path = os.path.join(self.tmp.name, name)
        with open(path, "w") as f:
            f.write(f"#!/bin/bash\nreal={ROLLBENCH}\n{body}\n")
        os.chmod(path, stat.S_IRWXU)
        return path

    def test_a_build_against_itself_is_the_same_in_every_run(self):
        r = same_results(ROLLBENCH, ROLLBENCH, *SMALL)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertEqual(r.stdout.splitlines()[-1], "12 runs (3 methods x 2 scenes x 2 settings; 0 of them ended with "
                         "a non-zero exit status in BASE): 12 the same, 0 different")

    def test_a_csv_one_line_longer_is_named_with_its_run(self):
        longer = self.wrapper("longer", '"$real" "$@"; rc=$?\nprev=\nfor a in "$@"; do\n'
                              '  [ "$prev" = --out ] && echo 0 >> "$a"; prev=$a\ndone\nexit $rc')
        csv = os.path.join(self.tmp.name, "plain.csv")
        subprocess.run([ROLLBENCH, "trajectory", "saddle", "--integrator", "rkmk4", "--h", "0.002", "--t-end", "0.3",
                        "--dt-out", "0.1", "--out", csv], check=True, capture_output=True)
        with open(csv) as f:
            added = len(f.read().splitlines()) + 1  # the line the wrapper adds
        r = same_results(ROLLBENCH, longer, *SMALL)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn(f"different: rkmk4 on saddle with --h 0.002: the CSV, from line {added}\n", r.stdout)
        self.assertIn("different: rk-bs32-adaptive on plane with --rtol 1e-8 --atol 1e-8: the CSV, from line "
                      f"{added}\n", r.stdout)
        self.assertIn(": 0 the same, 12 different", r.stdout)

    def test_an_exit_status_and_a_method_missing_from_the_registry_are_differences(self):
        failing = self.wrapper("failing", 'if [ "$1" = list ]; then "$real" "$@" | grep -v "^| rk4 |"; exit 0; fi\n'
                               '"$real" "$@"; exit 3')
        r = same_results(ROLLBENCH, failing, *SMALL)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual(lines[0], "different: rk4 is registered in BASE only")
        self.assertIn("different: rkmk4 on plane with --h 0.01: exit status 0 -> 3", lines)
        self.assertEqual(lines[-1], "8 runs (2 methods x 2 scenes x 2 settings; 0 of them ended with a non-zero exit "
                         "status in BASE): 0 the same, 8 different")

    def test_a_binary_that_does_not_run_is_refused_with_exit_2(self):
        r = same_results(ROLLBENCH, "/nonexistent/rollbench", *SMALL)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr, "same-results: /nonexistent/rollbench: No such file or directory\n")
        r = same_results(ROLLBENCH, ROLLBENCH, "--methods", "^nothing-registered$")
        self.assertEqual(r.returncode, 2)
        self.assertIn("same-results: no runs: 0 methods match '^nothing-registered$'", r.stderr)


class Reports(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        run = {"scene": "plane", "family": "rk", "adaptive": False, "status": "ok", "h": 0.01}
        self.base = {"schema": "rollbench.report/2", "created": "2026-12-06T18:59:01Z", "git": "abc",
                     "machine": {"load": [0.5, 0.4, 0.3]},
                     "error_components": [{"name": "contact", "label": "contact", "unit": "m"}],
                     "runs": [dict(run, integrator="rk4", error={"contact": 1.25e-7}, drift={"energy": -0.0},
                                   steps=100, wall_s={"median": 0.01, "samples": [0.01, 0.011]}),
                              dict(run, integrator="rkmk4", error={"contact": None}, steps=100,
                                   wall_s={"median": 0.02, "samples": [0.02]})]}

    def compare(self, changed):
        paths = []
        for name, report in (("a.json", self.base), ("b.json", changed)):
            paths.append(os.path.join(self.tmp.name, name))
            with open(paths[-1], "w") as f:
                json.dump(report, f)
        return same_results("--reports", *paths)

    def changed(self):
        return json.loads(json.dumps(self.base))

    def test_timings_and_metadata_aside_the_reports_are_the_same(self):
        b = self.changed()
        b["created"], b["git"], b["machine"]["load"] = "2026-12-07T00:00:00Z", "def", [1.5, 1.4, 1.3]
        b["runs"][0]["wall_s"] = {"median": 0.5, "samples": [0.5]}
        r = self.compare(b)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertTrue(r.stdout.endswith("(2 runs): the same, timings aside\n"), r.stdout)

    def test_a_value_moved_by_one_bit_is_named_by_its_path(self):
        b = self.changed()
        b["runs"][0]["error"]["contact"] = 1.2500000000000002e-7
        b["runs"][0]["drift"]["energy"] = 0.0
        b["runs"][1]["steps"] = 100.0
        r = self.compare(b)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertEqual(r.stdout.splitlines()[:3], ["different: runs[0].drift.energy: -0.0 -> 0.0",
                                                     "different: runs[0].error.contact: 1.25e-07 -> "
                                                     "1.2500000000000002e-07",
                                                     "different: runs[1].steps: 100 -> 100.0"])
        self.assertTrue(r.stdout.endswith("(2 runs): 3 values different\n"), r.stdout)

    def test_a_run_more_or_a_key_less_is_a_difference(self):
        b = self.changed()
        b["runs"].append(dict(b["runs"][0], integrator="euler"))
        del b["runs"][0]["steps"]
        r = self.compare(b)
        self.assertEqual(r.returncode, 1)
        self.assertIn("different: runs: 2 entries -> 3\n", r.stdout)
        self.assertIn("different: runs[0].steps: in A only\n", r.stdout)

    def test_an_unreadable_report_exits_2_naming_it(self):
        bad = os.path.join(self.tmp.name, "bad.json")
        with open(bad, "w") as f:
            f.write("{")
        r = same_results("--reports", bad, bad)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"same-results: '{bad}' is not JSON: "), r.stderr)
        with open(bad, "w") as f:
            json.dump({"name": "plane", "landscape": "0"}, f)  # a scene, not a report
        r = same_results("--reports", bad, bad)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr, f"same-results: {bad}: missing key 'schema' (expected \"rollbench.report/2\")\n")


if __name__ == "__main__":
    unittest.main()

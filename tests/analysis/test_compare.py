"""compare.py: no change against itself, a planted slowdown and nothing else,
timing noise not reported; and the rank test it rests on."""
import copy
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from analysis import compare
from analysis import report as rp
from tests.analysis import synthetic as syn

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run_cli(a, b, *extra):
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for name, report in (("a.json", a), ("b.json", b)):
            paths.append(os.path.join(tmp, name))
            with open(paths[-1], "w", encoding="utf-8") as f:
                json.dump(report, f)
        out = os.path.join(tmp, "compare.md")
        done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "compare.py"), *paths, "--out", out,
                               *extra], capture_output=True, text=True, cwd=tmp)
        with open(out, encoding="utf-8") as f:
            written = f.read()
    return done, written


class CompareReports(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.a = syn.make_report()

    def test_a_report_against_itself_has_no_change(self):
        result = compare.compare_reports(self.a, copy.deepcopy(self.a))
        self.assertEqual(result["changes"], [])
        self.assertEqual(len(result["runs"]), len(self.a["runs"]))
        self.assertEqual(result["only_a"] + result["only_b"], [])
        done, written = run_cli(self.a, self.a)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("No change", done.stdout)
        self.assertEqual(written.strip(), done.stdout.strip())

    def test_a_planted_slowdown_and_nothing_else(self):
        b = syn.slowed(self.a, 2.0)
        result = compare.compare_reports(self.a, b)
        per_run = [c for c in result["changes"] if c[1] == "time"]
        self.assertEqual(len(per_run), len(self.a["runs"]))
        self.assertEqual({kind for _, kind, _ in result["changes"]}, {"time", "time (pooled)"})
        self.assertEqual({key[1] for key, kind, _ in result["changes"] if kind == "time (pooled)"},
                         {r["integrator"] for r in self.a["runs"]})
        for row in result["runs"]:
            self.assertAlmostEqual(row["ratio"], 2.0, places=12)
            self.assertLess(row["p"], compare.ALPHA)
        done, _ = run_cli(self.a, b)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.count("×2 slower"), len(result["changes"]))
        self.assertNotIn("No change", done.stdout)

    def test_too_few_repeats_cannot_see_a_slowdown_and_say_so(self):
        def keep(report, n):
            out = copy.deepcopy(report)
            for run in out["runs"]:
                run["wall_s"]["samples"] = run["wall_s"]["samples"][:n]
            return out
        a2 = keep(self.a, 2)
        b2 = keep(syn.slowed(self.a, 2.0), 2)
        result = compare.compare_reports(a2, b2)
        # 2 against 2: the smallest p of a single run's test is 1/3; only the pooled test sees it
        self.assertEqual([kind for row in result["runs"] for kind, _ in row["changes"]], [])
        self.assertEqual({kind for _, kind, _ in result["changes"]}, {"time (pooled)"})
        self.assertAlmostEqual(compare.smallest_p(2, 2), 1.0 / 3.0)
        self.assertGreater(compare.smallest_p(4, 4), compare.ALPHA)
        self.assertLess(compare.smallest_p(5, 5), compare.ALPHA)
        # one run per method: nothing to pool either
        a1 = syn.subset(a2, "plane", list(syn.FIXED))
        a1["runs"] = [r for r in a1["runs"] if r["h"] == syn.HS[0]]
        b1 = syn.subset(b2, "plane", list(syn.FIXED))
        b1["runs"] = [r for r in b1["runs"] if r["h"] == syn.HS[0]]
        self.assertEqual(compare.compare_reports(a1, b1)["changes"], [])
        done, _ = run_cli(a1, b1)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertNotIn("No change:", done.stdout)
        self.assertIn("no timing change can be detected", done.stdout)
        done, _ = run_cli(a2, b2)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn(f"{len(a2['runs'])} of {len(a2['runs'])} runs have too few timed repeats (as few as 2)",
                      done.stdout)

    def test_a_slowdown_of_one_method_is_found_there_only(self):
        b = syn.slowed(self.a, 2.0, integrator="rkmk4")
        keys = {key for key, kind, _ in compare.compare_reports(self.a, b)["changes"]}
        mine = rp.by_integrator(rp.runs(self.a))["rkmk4"]
        self.assertEqual(keys, {(r.scene, r.integrator, rp.setting(r, 12)) for r in mine}
                         | {("all scenes", "rkmk4", f"{len(mine)} runs")})

    def test_timing_noise_is_not_change(self):
        b = copy.deepcopy(self.a)
        rng = np.random.default_rng(7)
        for run in b["runs"]:
            # the same distribution, resampled: overlapping samples, medians within a few per cent
            w = run["wall_s"]
            w["samples"] = list(np.array(w["samples"]) * rng.uniform(0.97, 1.03, len(w["samples"])))
            w["median"] = float(np.median(w["samples"]))
        self.assertEqual(compare.compare_reports(self.a, b)["changes"], [])

    def test_a_small_significant_shift_is_not_change(self):
        # quiet timings (0.1 % spread) 3 % slower: p < 0.01, but below the 5 % that counts
        a = copy.deepcopy(self.a)
        for run in a["runs"]:
            w = run["wall_s"]
            w["samples"] = [w["median"] * (1 + 0.001 * k) for k in (-2, -1, 0, 1, 2)]
        b = syn.slowed(a, 1.03)
        ratio, p, changed = compare.time_change(rp.runs(a)[0], rp.runs(b)[0])
        self.assertLess(p, compare.ALPHA)
        self.assertFalse(changed)
        self.assertEqual(compare.compare_reports(a, b)["changes"], [])

    def test_error_status_and_order_changes_are_reported(self):
        b = copy.deepcopy(self.a)
        run = b["runs"][3]
        run["error"]["contact"] *= 1.5
        b["runs"][4]["status"] = "diverged"
        b["orders"][0]["observed"]["contact"] += 0.5
        kinds = [kind for _, kind, _ in compare.compare_reports(self.a, b)["changes"]]
        self.assertEqual(sorted(kinds), ["error.contact", "order.contact", "status"])

    def test_a_report_of_another_schema_version_is_refused(self):
        old = copy.deepcopy(self.a)
        old["schema"] = "rollbench.report/1"
        with tempfile.TemporaryDirectory() as tmp:
            paths = [os.path.join(tmp, n) for n in ("old.json", "new.json")]
            for path, report in zip(paths, (old, self.a)):
                with open(path, "w", encoding="utf-8") as f:
                    json.dump(report, f)
            done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "compare.py"), *paths],
                                  capture_output=True, text=True)
        self.assertEqual(done.returncode, 2)
        self.assertIn("schema version 'rollbench.report/1' found, this analysis reads only "
                      "\"rollbench.report/2\"", done.stderr)
        self.assertIn("old.json", done.stderr)

    def test_rounding_level_drift_is_not_change(self):
        b = copy.deepcopy(self.a)
        for run in b["runs"]:
            if run["family"] == "rkmk":
                run["drift"]["rotation_defect"] *= 3  # 1e-15 -> 3e-15
        self.assertEqual(compare.compare_reports(self.a, b)["changes"], [])


def noisy(report, rng, sigma=0.05, repeats=3, factor=1.0, integrator=None):
    """A rerun: every run's samples drawn anew around its median (lognormal, sigma), one method slowed."""
    out = copy.deepcopy(report)
    for run in out["runs"]:
        w = run["wall_s"]
        scale = factor if integrator in (None, run["integrator"]) else 1.0
        w["samples"] = list(w["median"] * scale * rng.lognormal(0.0, sigma, repeats))
        w["median"], w["min"], w["max"] = (float(np.median(w["samples"])), min(w["samples"]), max(w["samples"]))
    return out


class PooledTime(unittest.TestCase):
    """A uniform 10 % slowdown of one method at 3 repeats: no single run can show it, the pooled test does."""

    @classmethod
    def setUpClass(cls):
        cls.base = syn.make_report()

    def test_a_ten_percent_slowdown_of_one_method_is_found(self):
        for seed in range(20):
            rng = np.random.default_rng(seed)
            a = noisy(self.base, rng)
            b = noisy(self.base, rng, factor=1.10, integrator="rkmk4")
            result = compare.compare_reports(a, b)
            pooled = result["pooled"]["rkmk4"]
            self.assertLess(pooled["p"], 0.01, seed)
            self.assertAlmostEqual(pooled["ratio"], 1.10, delta=0.05)
            self.assertTrue(pooled["changed"], seed)
            found = [(key, kind) for key, kind, _ in result["changes"]]
            self.assertEqual(found, [(("all scenes", "rkmk4", f"{pooled['runs']} runs"), "time (pooled)")], seed)
        done, _ = run_cli(a, b)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("| all scenes | rkmk4 |", done.stdout)
        self.assertRegex(done.stdout, r"\| time \(pooled\) \| ×1\.(0[6-9]|1[0-4])\d* slower")

    def test_reruns_of_the_same_code_report_no_change(self):
        for seed in range(20):
            rng = np.random.default_rng(100 + seed)
            result = compare.compare_reports(noisy(self.base, rng), noisy(self.base, rng))
            self.assertEqual(result["changes"], [], seed)
            self.assertTrue(all(t["runs"] >= compare.POOLED_MIN_RUNS for t in result["pooled"].values()))

    def test_a_speedup_is_found_too(self):
        rng = np.random.default_rng(1)
        result = compare.compare_reports(noisy(self.base, rng), noisy(self.base, rng, factor=0.9, integrator="rk4"))
        (key, kind, text), = result["changes"]
        self.assertEqual((key[1], kind), ("rk4", "time (pooled)"))
        self.assertRegex(text, r"^×0\.(8[5-9]|9[0-5]\d*) faster")

    def test_too_few_runs_are_not_pooled(self):
        a = syn.subset(self.base, "plane", ["rkmk4"])
        a["runs"] = a["runs"][:compare.POOLED_MIN_RUNS - 1]
        b = syn.slowed(a, 2.0)
        for run_a, run_b in zip(a["runs"], b["runs"]):
            run_a["wall_s"]["samples"] = run_a["wall_s"]["samples"][:3]
            run_b["wall_s"]["samples"] = run_b["wall_s"]["samples"][:3]
        result = compare.compare_reports(a, b)
        self.assertEqual(result["pooled"]["rkmk4"]["p"], 1.0)
        self.assertEqual(result["changes"], [])


class Comparable(unittest.TestCase):
    """Reports with other end times or output grids are refused, naming both; other ladders are stated."""

    @classmethod
    def setUpClass(cls):
        cls.a = syn.make_report()
        for ref in cls.a["references"]:
            ref["t_end"] = 5.0
        cls.a["options"] = {"t_end": None, "dt_out": None, "error_dt": 0.25, "h": syn.HS, "tol": syn.TOLS}

    def test_another_end_time_is_refused(self):
        b = copy.deepcopy(self.a)
        b["references"][1]["t_end"] = 10.0
        with self.assertRaises(compare.Mismatch) as caught:
            compare.check_comparable(self.a, b, "old.json", "new.json")
        self.assertEqual(str(caught.exception), "the reports do not measure the same runs: scene 'valley-sideways' "
                         "ends at t = 5 in old.json but at t = 10 in new.json")
        with tempfile.TemporaryDirectory() as tmp:
            paths = [os.path.join(tmp, n) for n in ("a.json", "b.json")]
            for path, report in zip(paths, (self.a, b)):
                with open(path, "w", encoding="utf-8") as f:
                    json.dump(report, f)
            done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "compare.py"), *paths],
                                  capture_output=True, text=True)
        self.assertEqual(done.returncode, 2)
        self.assertEqual(done.stdout, "")
        self.assertIn(f"scene 'valley-sideways' ends at t = 5 in {paths[0]} but at t = 10 in {paths[1]}", done.stderr)

    def test_another_output_or_error_grid_is_refused(self):
        b = copy.deepcopy(self.a)
        b["options"]["dt_out"] = 0.1
        b["options"]["error_dt"] = 0.5
        with self.assertRaises(compare.Mismatch) as caught:
            compare.check_comparable(self.a, b)
        self.assertIn("the output grid dt_out is none in A but 0.1 in B", str(caught.exception))
        self.assertIn("the error grid error_dt is 0.25 in A but 0.5 in B", str(caught.exception))

    def test_the_same_sweep_passes_and_another_ladder_is_stated(self):
        compare.check_comparable(self.a, copy.deepcopy(self.a))
        self.assertIsNone(compare.ladder_note(self.a, copy.deepcopy(self.a)))
        b = copy.deepcopy(self.a)
        b["options"]["h"] = syn.HS[:-1]
        b["runs"] = [r for r in b["runs"] if r["adaptive"] or r["h"] != syn.HS[-1]]
        compare.check_comparable(self.a, b)
        self.assertEqual(compare.ladder_note(self.a, b), f"Note: the step ladder differs ({len(syn.HS)} values in A, "
                         f"{len(syn.HS) - 1} in B): only the runs in both are compared (listed below).")


def timed(samples):
    return rp.Run.of({"scene": "plane", "integrator": "rk4", "adaptive": False, "status": "ok", "h": 0.1,
                      "wall_s": {"samples": list(samples), "median": float(np.median(samples))}})


class TimeChange(unittest.TestCase):
    """compare.time_change on raw samples (the rank test is SciPy's Mann-Whitney U)."""

    def test_exact_small_samples(self):
        # 5 against 5, completely separated: p = 2 / C(10, 5) (exact, not the normal approximation)
        ratio, p, changed = compare.time_change(timed([1, 2, 3, 4, 5]), timed([6, 7, 8, 9, 10]))
        self.assertAlmostEqual(p, 2 / math.comb(10, 5), places=15)
        self.assertAlmostEqual(ratio, 8 / 3, places=15)
        self.assertTrue(changed)
        # 2 against 2 can never be significant
        _, p, changed = compare.time_change(timed([1, 2]), timed([3, 4]))
        self.assertAlmostEqual(p, 2 / math.comb(4, 2), places=15)
        self.assertFalse(changed)

    def test_identical_samples(self):
        self.assertEqual(compare.time_change(timed([1.0] * 5), timed([1.0] * 5))[1:], (1.0, False))
        self.assertEqual(compare.time_change(timed([1, 2, 3]), timed([1, 2, 3]))[1:], (1.0, False))

    def test_large_samples_separate_shifted_distributions(self):
        rng = np.random.default_rng(3)
        a = rng.lognormal(0.0, 0.1, 40)
        self.assertLess(compare.time_change(timed(a), timed(a * 1.2))[1], 1e-6)
        self.assertGreater(compare.time_change(timed(a), timed(rng.permutation(a)))[1], 0.99)


if __name__ == "__main__":
    unittest.main()

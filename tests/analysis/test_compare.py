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

from analysis import compare, ranktest
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
        self.assertEqual(len(result["changes"]), len(self.a["runs"]))
        self.assertEqual({kind for _, kind, _ in result["changes"]}, {"time"})
        for row in result["runs"]:
            self.assertAlmostEqual(row["ratio"], 2.0, places=12)
            self.assertLess(row["p"], compare.ALPHA)
        done, _ = run_cli(self.a, b)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.count("×2 slower"), len(self.a["runs"]))
        self.assertNotIn("No change", done.stdout)

    def test_a_slowdown_of_one_method_is_found_there_only(self):
        b = syn.slowed(self.a, 2.0, integrator="rkmk4")
        keys = {key for key, kind, _ in compare.compare_reports(self.a, b)["changes"]}
        self.assertEqual(keys, {(r["scene"], r["integrator"], compare.rp.setting(r, 12))
                                for r in self.a["runs"] if r["integrator"] == "rkmk4"})

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
        ratio, p, changed = compare.time_change(a["runs"][0], b["runs"][0])
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

    def test_rounding_level_drift_is_not_change(self):
        b = copy.deepcopy(self.a)
        for run in b["runs"]:
            if run["family"] == "rkmk":
                run["drift"]["rotation_defect"] *= 3  # 1e-15 -> 3e-15
        self.assertEqual(compare.compare_reports(self.a, b)["changes"], [])


class MannWhitney(unittest.TestCase):
    def test_exact_small_samples(self):
        # 5 against 5, completely separated: p = 2 / C(10, 5)
        u, p = ranktest.mann_whitney([1, 2, 3, 4, 5], [6, 7, 8, 9, 10])
        self.assertEqual(u, 0.0)
        self.assertAlmostEqual(p, 2 / math.comb(10, 5), places=15)
        # 2 against 2 can never be significant
        self.assertAlmostEqual(ranktest.mann_whitney([1, 2], [3, 4])[1], 2 / math.comb(4, 2), places=15)

    def test_exact_distribution_counts_every_ordering(self):
        for n1, n2 in ((1, 1), (3, 4), (6, 5)):
            counts = np.array(ranktest._u_counts(n1, n2))
            self.assertEqual(counts.sum(), math.comb(n1 + n2, n1))
            np.testing.assert_array_equal(counts, counts[::-1])  # symmetric about n1 n2 / 2

    def test_identical_samples(self):
        self.assertEqual(ranktest.mann_whitney([1.0] * 5, [1.0] * 5)[1], 1.0)
        self.assertEqual(ranktest.mann_whitney([1, 2, 3], [1, 2, 3])[1], 1.0)
        self.assertEqual(ranktest.mann_whitney([], [1, 2])[1], 1.0)

    def test_normal_approximation_with_ties(self):
        # ties force the normal approximation; the U statistic is the count of pairs a > b (+1/2 per tie)
        a, b = [1, 2, 2, 3, 3, 3, 4], [2, 3, 4, 4, 5, 5, 6]
        u, p = ranktest.mann_whitney(a, b)
        pairs = sum((x > y) + 0.5 * (x == y) for x in a for y in b)
        self.assertEqual(u, pairs)
        self.assertTrue(0.01 < p < 0.1)
        self.assertAlmostEqual(ranktest.mann_whitney(b, a)[1], p, places=15)

    def test_large_samples_separate_shifted_distributions(self):
        rng = np.random.default_rng(3)
        a = rng.lognormal(0.0, 0.1, 40)
        self.assertLess(ranktest.mann_whitney(a, a * 1.2)[1], 1e-6)
        self.assertGreater(ranktest.mann_whitney(a, rng.permutation(a))[1], 0.99)


if __name__ == "__main__":
    unittest.main()

"""The Lie frontier (analysis/frontier.py) on synthetic reports whose costs are known."""
import math
import unittest

from analysis import costs, frontier
from analysis import report as rp
from tests.analysis import synthetic as syn


def expected_cost(name, target, scene="valley-sideways"):
    """Median wall time to reach target, straight from the synthetic model (error = a tol^s, cost ~ tol^(-1/q))."""
    runs = rp.by_integrator(rp.runs(syn.make_report(), scene))[name]
    return costs.reach(runs, (target,), "contact", syn.SCENES[scene][1])[target][0]


class Frontier(unittest.TestCase):
    def setUp(self):
        self.report = syn.make_report()

    def test_the_sides_come_from_on_group_and_family(self):
        lie, library = frontier.sides(rp.runs(self.report, "valley-sideways"))
        self.assertEqual(set(lie), {n for n, f in {**{k: v[0] for k, v in syn.FIXED.items()},
                                                   **{k: v[0] for k, v in syn.ADAPTIVE.items()}}.items()
                                    if f == "rkmk"})
        self.assertIn("gsl-rkf45-adaptive", library)
        self.assertIn("odeint-rk4", library)
        self.assertNotIn("rk4", library)  # the suite's own flat methods are not a library

    def test_the_ratio_is_the_best_lie_over_the_best_library(self):
        with rp.errors_read("max"):
            for target in costs.TARGETS:
                lie, library, ratio = frontier.frontier(self.report, "valley-sideways", "contact", target)
                lie_side, library_side = frontier.sides(rp.runs(self.report, "valley-sideways"))
                best = {side: min(lie_side if side == "lie" else library_side,
                                  key=lambda n: (math.inf if math.isnan(c := expected_cost(n, target)) else c))
                        for side in ("lie", "library")}
                self.assertEqual((lie, library), (best["lie"], best["library"]))
                median, low, high, repeats, _ = ratio
                self.assertAlmostEqual(median, expected_cost(lie, target) / expected_cost(library, target), places=9)
                self.assertLessEqual(low, median)
                self.assertLessEqual(median, high)
                self.assertEqual(repeats, len(syn.SAMPLE_SPREAD))

    def test_a_slower_lie_side_raises_the_ratio_by_that_factor(self):
        with rp.errors_read("max"):
            lie, library, ratio = frontier.frontier(self.report, "valley-sideways", "contact", 1e-6)
            slowed = syn.slowed(self.report, 2.0, lie)
            lie2, library2, ratio2 = frontier.frontier(slowed, "valley-sideways", "contact", 1e-6)
        if lie2 == lie:
            self.assertAlmostEqual(ratio2[0], 2 * ratio[0], places=9)
        else:  # another Lie method is now the best, and no worse than twice
            self.assertLessEqual(ratio2[0], 2 * ratio[0] * (1 + 1e-12))
        self.assertEqual(library2, library)

    def test_no_library_method_means_no_frontier(self):
        only_lie = syn.subset(self.report, "valley-sideways", ["rkmk4", "rkmk-dp54-adaptive"])
        self.assertIsNone(frontier.frontier(only_lie, "valley-sideways", "contact", 1e-6))


if __name__ == "__main__":
    unittest.main()


class FrontierFinding(unittest.TestCase):
    def test_the_findings_state_the_frontier_on_the_scenes_where_r_feeds_back(self):
        from analysis import findings
        report = syn.make_report()
        text = "\n".join(findings.findings_section(report, "contact"))
        line = next(x for x in text.splitlines() if x.startswith("- The Lie frontier"))
        with rp.errors_read("max"):
            for target in costs.TARGETS:
                lie, library, ratio = frontier.frontier(report, "valley-sideways", "contact", target)
                self.assertIn(f"valley-sideways at {target:.0e}: {lie} / {library} {findings.ratio_text(ratio)}", line)
        self.assertNotIn("plane at", line)  # homogeneous: R does not feed back

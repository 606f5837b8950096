"""summary.md on a synthetic report: the orders and the cost-to-accuracy
numbers must be what the synthetic model says, computed here from the model."""
import math
import unittest

from analysis import report as rp
from analysis import summary
from tests.analysis import synthetic as syn

REL = 6e-3  # the tables print 3 significant digits


def ok_settings(scene, name, settings):
    return [s for s in settings if (scene, name, s) not in syn.FAILURES]


def model_cost(scene, name, kind, target):
    """(cost, bound) the summary must print, from the synthetic model alone.

    Along a power law the log-log interpolation is exact, so inside the
    measured range the cost is the model's; "≤" where even the cheapest run
    is below the target; NaN where no run reaches it.
    """
    if name in syn.FIXED:
        settings = ok_settings(scene, name, syn.HS)
        error = lambda h: syn.fixed_error(scene, name, h)  # noqa: E731
        cost = syn.fixed_wall if kind == "time" else syn.fixed_rhs
        _, p, _, c, _, _, _ = syn.FIXED[name]
        # error = C h^p  =>  h = (target / C)^(1/p)
        inverse = lambda t: (t / (c * syn.SCENE_FACTOR[scene])) ** (1.0 / p)  # noqa: E731
    else:
        settings = ok_settings(scene, name, syn.TOLS)
        error = lambda tol: syn.adaptive_error(scene, name, tol)  # noqa: E731
        cost = syn.adaptive_wall if kind == "time" else syn.adaptive_rhs
        inverse = lambda t: t / (syn.ADAPTIVE[name][2] * syn.SCENE_FACTOR[scene])  # noqa: E731
    cheapest = min(settings, key=lambda s: cost(name, s))
    if error(cheapest) <= target:
        return cost(name, cheapest), "≤"
    if min(error(s) for s in settings) > target:
        return math.nan, ""
    return cost(name, inverse(target)), ""


class SummaryOfSyntheticReport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = syn.make_report()
        cls.markdown = summary.summary_markdown(cls.report)

    def order_rows(self, markdown):
        rows = summary.parse_table(markdown, "## Observed order")
        return {(r[0], r[1]): r for r in rows}

    def check_orders(self, markdown):
        rows = self.order_rows(markdown)
        self.assertEqual(len(rows), len(syn.SCENES) * len(syn.FIXED))
        for scene in syn.SCENES:
            for name, (_, p, prot, *_rest) in syn.FIXED.items():
                row = rows[(scene, name)]
                with self.subTest(scene=scene, integrator=name):
                    self.assertEqual(row[2], str(p))
                    self.assertEqual(row[3].split(" ")[0], f"{p:.2f}")
                    self.assertEqual(row[4], str(prot))
                    self.assertEqual(row[5].split(" ")[0], f"{prot:.2f}")
                    self.assertEqual(row[7], "pass")

    def test_printed_orders_are_the_model_orders(self):
        self.check_orders(self.markdown)

    def test_orders_are_fitted_when_the_report_has_none(self):
        report = syn.minimal_report()
        markdown = summary.summary_markdown(report)
        self.assertIn("fitted here", markdown)
        self.check_orders(markdown)
        for o in rp.orders(report):
            p, prot = syn.FIXED[o["integrator"]][1:3]
            self.assertAlmostEqual(o["observed"]["contact"], p, places=9)
            self.assertAlmostEqual(o["observed"]["rotation"], prot, places=9)

    def test_cost_to_accuracy_follows_the_model(self):
        header_kinds = [(kind, target) for target in summary.TARGETS for kind in ("time", "rhs")]
        seen = {"interpolated": 0, "bound": 0, "never": 0}
        for scene in syn.SCENES:
            rows = summary.parse_table(self.markdown, f"### Cost to accuracy — {scene}")
            self.assertEqual([r[0] for r in rows], list(syn.FIXED) + list(syn.ADAPTIVE))
            for row in rows:
                name = row[0]
                for cell, (kind, target) in zip(row[2:], header_kinds):
                    cost, bound = model_cost(scene, name, kind, target)
                    with self.subTest(scene=scene, integrator=name, kind=kind, target=target, cell=cell):
                        if math.isnan(cost):
                            self.assertEqual(cell, "—")
                            seen["never"] += 1
                        else:
                            self.assertEqual(cell.startswith("≤"), bound == "≤")
                            self.assertTrue(math.isclose(summary.as_number(cell), cost, rel_tol=REL),
                                            f"{cell} != {cost:.4g}")
                            seen["bound" if bound else "interpolated"] += 1
        # the synthetic report exercises all three cases
        self.assertTrue(all(seen.values()), seen)

    def test_cheapest_method_per_accuracy(self):
        rows = summary.parse_table(self.markdown, "## Cheapest method per accuracy")
        self.assertEqual(len(rows), len(syn.SCENES) * len(summary.TARGETS))
        for scene, target_text, by_time, by_rhs in rows:
            target = float(target_text)
            for cell, kind in ((by_time, "time"), (by_rhs, "rhs")):
                costs = {n: model_cost(scene, n, kind, target) for n in list(syn.FIXED) + list(syn.ADAPTIVE)}
                (cost, bound), name = min((c, n) for n, c in costs.items() if not math.isnan(c[0]))
                with self.subTest(scene=scene, target=target, kind=kind):
                    self.assertTrue(cell.startswith(name + " ("), cell)
                    inside = cell.split("(")[1].rstrip(")")
                    self.assertEqual(inside.startswith("≤"), bound == "≤")
                    self.assertTrue(math.isclose(summary.as_number(inside), cost, rel_tol=REL))

    def test_every_failure_is_listed(self):
        rows = summary.parse_table(self.markdown, "## Failures")
        listed = {(r[0], r[1], r[3]) for r in rows}
        for (scene, name, _), (status, _, _) in syn.FAILURES.items():
            self.assertIn((scene, name, status), listed)
        drift_failures = [d for d in self.report["stability"]["drift"] if d["status"] != "ok"]
        self.assertEqual(len(rows), len(syn.FAILURES) + len(drift_failures))
        # a '|' in a message is escaped, not a column break
        self.assertIn("gsl: step size underflow \\| h < 1e-15", self.markdown)


class CostInterpolation(unittest.TestCase):
    def test_log_log_interpolation_is_exact_on_a_power_law(self):
        points = [(10.0 ** k, 10.0 ** (-2 * k)) for k in range(1, 5)]  # error = cost^-2
        cost, bound = summary.cost_to_reach(points, 1e-5)
        self.assertAlmostEqual(cost, 10 ** 2.5, places=9)
        self.assertEqual(bound, "")

    def test_first_crossing_on_a_non_monotone_curve(self):
        points = [(1.0, 1e-2), (2.0, 1e-4), (4.0, 1e-3), (8.0, 1e-6)]
        cost, _ = summary.cost_to_reach(points, 1e-3)
        self.assertAlmostEqual(cost, math.sqrt(2.0), places=9)

    def test_never_and_bound(self):
        self.assertTrue(math.isnan(summary.cost_to_reach([(1.0, 1e-3), (2.0, 1e-4)], 1e-9)[0]))
        self.assertEqual(summary.cost_to_reach([(1.0, 1e-3), (2.0, 1e-4)], 1e-2), (1.0, "≤"))
        self.assertTrue(math.isnan(summary.cost_to_reach([], 1e-2)[0]))


if __name__ == "__main__":
    unittest.main()

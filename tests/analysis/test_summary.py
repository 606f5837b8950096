"""summary.md on a synthetic report: the orders and verdicts as the report
gives them, and the cost-to-accuracy numbers, same-tableau pairs, tolerance
fits and stability steps as the synthetic model says, computed here from
the model."""
import math
import unittest

from analysis import costs, pairs, summary
from analysis import markdown as md
from analysis import report as rp
from tests.analysis import synthetic as syn

REL = 6e-3  # the tables print 3 significant digits


def ok_settings(scene, name, settings):
    return [s for s in settings if (scene, name, s) not in syn.FAILURES]


def model_place(scene, name, kind, target, metric="worst"):
    """(setting where the metric reaches target, cost there, bound) from the model alone.

    Along a power law the log-log interpolation is exact, so inside the
    measured range the setting and cost are the model's; "≤" where even
    the cheapest run is below the target; NaNs where no run reaches it.
    """
    if name in syn.FIXED:
        settings = ok_settings(scene, name, syn.HS)
        law = syn.fixed_law(scene, name, metric)
        cost = syn.fixed_wall if kind == "time" else syn.fixed_rhs
    else:
        settings = ok_settings(scene, name, syn.TOLS)
        law = syn.adaptive_law(scene, name, metric)
        cost = syn.adaptive_wall if kind == "time" else syn.adaptive_rhs
    error = lambda s: law[0] * s ** law[1]  # noqa: E731
    cheapest = min(settings, key=lambda s: cost(name, s))
    if error(cheapest) <= target:
        return cheapest, cost(name, cheapest), "≤"
    if min(error(s) for s in settings) > target:
        return math.nan, math.nan, ""
    setting = (target / law[0]) ** (1.0 / law[1])
    return setting, cost(name, setting), ""


def model_cost(scene, name, kind, target, metric="worst"):
    _, cost, bound = model_place(scene, name, kind, target, metric)
    return cost, bound


def finer_setting(scene, name, target):
    """The first run of the sweep (cheapest first) at or below the target: the bracket's accurate end."""
    if name in syn.FIXED:
        grid = sorted(ok_settings(scene, name, syn.HS), reverse=True)
        return next((h for h in grid if syn.fixed_error(scene, name, h, "worst") <= target), grid[-1])
    grid = sorted(ok_settings(scene, name, syn.TOLS), reverse=True)
    return next((t for t in grid if syn.adaptive_error(scene, name, t, "worst") <= target), grid[-1])


def model_rotation(scene, name, setting):
    if name in syn.FIXED:
        return syn.fixed_error(scene, name, setting, "rotation")
    return syn.adaptive_error(scene, name, setting, "rotation")


class SummaryOfSyntheticReport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = syn.make_report()
        cls.markdown = summary.summary_markdown(cls.report)

    def test_printed_orders_and_verdicts_are_the_reports(self):
        rows = {(r[0], r[1]): r for r in md.parse_table(self.markdown, "## Observed order")}
        self.assertEqual(len(rows), len(syn.SCENES) * len(syn.FIXED))
        for o in self.report["orders"]:
            row = rows[(o["scene"], o["integrator"])]
            verdict, ci = syn.PLANTED_VERDICTS.get((o["scene"], o["integrator"]), ("as declared", 0.01))
            p, prot = syn.FIXED[o["integrator"]][1:3]
            with self.subTest(scene=o["scene"], integrator=o["integrator"]):
                self.assertEqual(row[2:4], [str(p), str(prot)])
                for cell, c in zip(row[4:8], ("contact", "centre", "omega", "rotation")):
                    self.assertEqual(cell, f"{o['observed'][c]:.2f} ± {ci:.2f} ({verdict})")
                self.assertEqual(row[-1], {"lower": "**lower**"}.get(verdict, verdict))
        # the planted cases are not shown as passing
        self.assertEqual(rows[("plane", "rkmk8")][-1], "inconclusive")
        self.assertEqual(rows[("valley-sideways", "gsl-rk4")][-1], "**lower**")
        self.assertEqual(rows[("plane", "rk4")][-1], "as declared")

    def test_an_interval_given_as_low_high(self):
        report = syn.subset(self.report, "plane", ["rk4"])
        order = dict(report["orders"][0], ci95={"contact": [3.9, 4.1]}, verdict={"contact": "as declared"})
        self.assertEqual(summary._order_cell(order, "contact"),
                         f"{order['observed']['contact']:.2f} [3.90, 4.10] (as declared)")

    def test_an_exact_component_has_no_slope_and_says_exact(self):
        order = {"observed": {"contact": 4.01, "omega": None}, "ci95": {"contact": 0.02, "omega": None},
                 "verdict": {"contact": "as declared", "omega": "exact"}}
        self.assertEqual(summary._order_cell(order, "omega"), "exact")
        # exact counts for neither side of the overall verdict
        self.assertEqual(summary.overall_verdict(order, ["contact", "omega"]), "as declared")
        order["verdict"]["contact"] = "lower"
        self.assertEqual(summary.overall_verdict(order, ["contact", "omega"]), "**lower**")
        self.assertEqual(summary.overall_verdict(order, ["omega"]), "exact")

    def test_without_orders_nothing_is_fitted_here(self):
        markdown = summary.summary_markdown(syn.minimal_report())
        self.assertIn("The report has no `orders` section", markdown)
        self.assertEqual(md.parse_table(markdown, "## Observed order"), [])

    def test_cost_to_accuracy_follows_the_model(self):
        self.check_costs(self.markdown, "worst")

    def test_another_metric_gives_other_costs(self):
        markdown = summary.summary_markdown(self.report, "contact")
        self.assertIn("## Cost to accuracy (contact error)", markdown)
        self.check_costs(markdown, "contact")
        # rk4's worst error is its rotation error (9 h^4), its contact error smaller (2 h^4): cheaper by contact
        by_worst = md.parse_table(self.markdown, "### Cost to accuracy — plane")
        by_contact = md.parse_table(markdown, "### Cost to accuracy — plane")
        rk4 = [r for r in by_worst if r[0] == "rk4"][0], [r for r in by_contact if r[0] == "rk4"][0]
        self.assertLess(md.as_number(rk4[1][3]), md.as_number(rk4[0][3]))

    def check_costs(self, markdown, metric):
        header_kinds = [(kind, target) for target in costs.TARGETS for kind in ("time", "rhs")]
        seen = {"interpolated": 0, "bound": 0, "never": 0}
        for scene in syn.SCENES:
            rows = md.parse_table(markdown, f"### Cost to accuracy — {scene}")
            self.assertEqual([r[0] for r in rows], list(syn.FIXED) + list(syn.ADAPTIVE))
            for row in rows:
                name = row[0]
                for cell, (kind, target) in zip(row[2:], header_kinds):
                    cost, bound = model_cost(scene, name, kind, target, metric)
                    with self.subTest(scene=scene, integrator=name, kind=kind, target=target, cell=cell):
                        if math.isnan(cost):
                            self.assertEqual(cell, "—")
                            seen["never"] += 1
                        else:
                            self.assertEqual(cell.startswith("≤"), bound == "≤")
                            self.assertTrue(math.isclose(md.as_number(cell), cost, rel_tol=REL),
                                            f"{cell} != {cost:.4g}")
                            seen["bound" if bound else "interpolated"] += 1
        # the synthetic report exercises all three cases
        self.assertTrue(all(seen.values()), seen)

    def test_cheapest_method_per_accuracy(self):
        rows = md.parse_table(self.markdown, "## Cheapest method per accuracy (worst error)")
        self.assertEqual(len(rows), len(syn.SCENES) * len(costs.TARGETS))
        for scene, target_text, by_time, by_rhs in rows:
            target = float(target_text)
            for cell, kind in ((by_time, "time"), (by_rhs, "rhs")):
                found = {n: model_cost(scene, n, kind, target) for n in list(syn.FIXED) + list(syn.ADAPTIVE)}
                (cost, bound), name = min((c, n) for n, c in found.items() if not math.isnan(c[0]))
                with self.subTest(scene=scene, target=target, kind=kind):
                    self.assertTrue(cell.startswith(name + " ("), cell)
                    inside = cell.split("(")[1].rstrip(")")
                    self.assertEqual(inside.startswith("≤"), bound == "≤")
                    self.assertTrue(math.isclose(md.as_number(inside), cost, rel_tol=REL))

    def test_same_tableau_pairs_follow_the_model(self):
        checked = 0
        for scene in syn.SCENES:
            rows = md.parse_table(self.markdown, f"### Same tableau — {scene}")
            self.assertEqual(len(rows), len(syn.PAIRS) * len(costs.TARGETS) * 2)
            self.assertEqual({tuple(r[0].split(" / ")) for r in rows}, set(syn.PAIRS))
            for pair, target_text, name, _, time_cell, rhs_cell, rotation_cell in rows:
                target = float(target_text)
                setting, rhs, bound = model_place(scene, name, "rhs", target)
                with self.subTest(scene=scene, integrator=name, target=target):
                    self.assertIn(name, pair.split(" / "))
                    self.assertTrue(math.isclose(md.as_number(time_cell), model_cost(scene, name, "time", target)[0],
                                                 rel_tol=REL))
                    self.assertTrue(math.isclose(md.as_number(rhs_cell), rhs, rel_tol=REL))
                    self.assertEqual(rhs_cell.startswith("≤"), bound == "≤")
                    floor = syn.SCENES[scene][1]
                    rotation = max(model_rotation(scene, name, setting), floor)
                    if model_rotation(scene, name, finer_setting(scene, name, target)) < floor:
                        # a bracketing run's rotation counts as the floor: the value is an upper bound
                        self.assertGreaterEqual(md.as_number(rotation_cell), rotation * (1 - REL))
                    else:
                        self.assertTrue(math.isclose(md.as_number(rotation_cell), rotation, rel_tol=REL),
                                        f"{rotation_cell} != {rotation:.4g}")
                    checked += 1
        self.assertEqual(checked, len(syn.SCENES) * len(syn.PAIRS) * len(costs.TARGETS) * 2)
        # the Lie method's R is closer at the same worst error: the point of the table
        rows = md.parse_table(self.markdown, "### Same tableau — plane")
        by_name = {(r[2], r[1]): md.as_number(r[6]) for r in rows}
        for flat, lie in syn.PAIRS:
            self.assertLess(by_name[(lie, "1e-06")], by_name[(flat, "1e-06")])

    def test_no_pair_says_so(self):
        report = syn.subset(self.report, "plane", ["rk4", "euler"])
        self.assertIn("No same-tableau pair ran in this report", "\n".join(pairs.pairs_section(report)))
        self.assertNotIn("### Same tableau", "\n".join(pairs.pairs_section(report)))

    def test_tolerance_fits_are_shown(self):
        rows = md.parse_table(self.markdown, "## Tolerance proportionality")
        self.assertEqual(len(rows), len(syn.SCENES) * len(syn.ADAPTIVE))
        declared = {(r["scene"], r["integrator"]): str(r["declared_order"]) for r in self.report["runs"]}
        for scene, name, order, step_order, slope, intercept, residual, points in rows:
            self.assertEqual(order, declared[(scene, name)])
            self.assertEqual(step_order, "—")  # the synthetic fits have none
            a, s = syn.adaptive_law(scene, name, "worst")
            self.assertEqual(slope, md.fmt(s))
            self.assertTrue(math.isclose(float(intercept), math.log10(a), rel_tol=REL))
            self.assertEqual((residual, points), ("0", str(len(syn.TOLS))))

    def test_stability_with_the_accuracy_beside_and_how_the_next_step_fails(self):
        rows = {(r[0], r[1]): r for r in md.parse_table(self.markdown, "## Stability")}
        self.assertEqual(len(rows), len(syn.SCENES) * len(syn.STABLE_H))
        expected = {"rotation-defect": "rotation defect 0.7 > 0.5", "energy": "energy error 1.5 > 1 of the scale",
                    "stopped": "chart-limit",
                    "energy-growth": "exponential growth of the energy error (slope 2 → 4)"}
        for (scene, name), row in rows.items():
            failure = expected[syn.STABILITY_FAILURE[name]]
            if scene == "valley-sideways" and name == "euler":
                self.assertEqual(row[2:5], ["none", "—", "—"])
                self.assertEqual(row[5], f"{min(syn.STABILITY_HS):.3g} – {min(syn.STABILITY_HS):.3g} (1)")
                self.assertEqual(row[6], f"{failure} (h = {md.fmt(min(syn.STABILITY_HS))})")
                continue
            h = syn.STABLE_H[name]
            self.assertEqual(float(row[2]), float(f"{h:.3g}"))
            self.assertEqual(float(row[3]), float(f"{syn.ROTATION_DEFECT[name]:.3g}"))
            self.assertEqual(float(row[4]), float(f"{syn.ENERGY_ERROR[name]:.3g}"))
            self.assertEqual(row[6], f"{failure} (h = {md.fmt(2 * h)})")
        self.assertIn("run to t = 10 s without failing", self.markdown)
        self.assertIn("passes 1 of the energy scale, when ‖RᵀR − I‖_F passes 0.5", self.markdown)

    def test_every_failure_is_listed(self):
        rows = md.parse_table(self.markdown, "## Failures")
        listed = {(r[0], r[1], r[3]) for r in rows}
        for (scene, name, _), (status, _, _) in syn.FAILURES.items():
            self.assertIn((scene, name, status), listed)
        drift_failures = [d for d in self.report["stability"]["drift"] if d["status"] != "ok"]
        self.assertEqual(len(rows), len(syn.FAILURES) + len(drift_failures))
        # a '|' in a message is escaped, not a column break
        self.assertIn("gsl: step size underflow \\| h < 1e-15", self.markdown)


class CostInterpolation(unittest.TestCase):
    @staticmethod
    def points(pairs_):
        return [(c, e, None) for c, e in pairs_]

    def test_log_log_interpolation_is_exact_on_a_power_law(self):
        points = self.points((10.0 ** k, 10.0 ** (-2 * k)) for k in range(1, 5))  # error = cost^-2
        cost, bound = costs.cost_to_reach(points, 1e-5)
        self.assertAlmostEqual(cost, 10 ** 2.5, places=9)
        self.assertEqual(bound, "")

    def test_first_crossing_on_a_non_monotone_curve(self):
        points = self.points([(1.0, 1e-2), (2.0, 1e-4), (4.0, 1e-3), (8.0, 1e-6)])
        cost, _ = costs.cost_to_reach(points, 1e-3)
        self.assertAlmostEqual(cost, math.sqrt(2.0), places=9)

    def test_another_value_interpolated_at_the_same_place(self):
        runs = [{"v": 1e-2}, {"v": 1e-6}]
        points = [(1.0, 1e-2, runs[0]), (100.0, 1e-6, runs[1])]
        cost, value, bound = costs.at_crossing(points, 1e-4, lambda r: r["v"])
        self.assertAlmostEqual(cost, 10.0, places=9)
        self.assertAlmostEqual(value, 1e-4, places=15)
        self.assertEqual(bound, "")

    def test_never_and_bound(self):
        self.assertTrue(math.isnan(costs.cost_to_reach(self.points([(1.0, 1e-3), (2.0, 1e-4)]), 1e-9)[0]))
        self.assertEqual(costs.cost_to_reach(self.points([(1.0, 1e-3), (2.0, 1e-4)]), 1e-2), (1.0, "≤"))
        self.assertTrue(math.isnan(costs.cost_to_reach([], 1e-2)[0]))


class ErrorComponentsOfTheReport(unittest.TestCase):
    def test_the_error_components_come_from_the_report(self):
        report = syn.make_report()
        self.assertEqual(rp.components(report), ("contact", "centre", "omega", "rotation"))
        self.assertEqual(rp.metric_label(report, "omega"), "angular-velocity error (rad/s)")
        # a report that lists fewer components shows only those
        report["error_components"] = [c for c in report["error_components"] if c["name"] in ("contact", "rotation")]
        self.assertEqual(rp.metrics(report), ("worst", "contact", "rotation"))
        header = next(line for line in summary.orders_section(report) if line.startswith("| scene"))
        self.assertEqual(header, "| scene | integrator | declared | declared (R) | contact | rotation | "
                                 "fit range h (contact) | verdict |")
        with self.assertRaisesRegex(rp.ReportError, "no error component 'omega' in the report"):
            rp.metric_label(report, "omega")


if __name__ == "__main__":
    unittest.main()

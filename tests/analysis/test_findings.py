"""The findings that open summary.md: first before everything else, the
scene's kind from the report, the cheapest method and the flat/Lie time
ratios as the synthetic model says (computed here), pairs from the
methods' tableau facts (a user's rk-X / rkmk-X too), the spread over
repeats, the verdict counts, and the best-of-family pick by cost."""
import copy
import json
import math
import os
import subprocess
import tempfile
import unittest

from analysis import costs, figures_precision, findings, pairs, summary
from analysis import markdown as md
from analysis import report as rp
from tests.analysis import synthetic as syn
from tests.analysis.test_summary import REL, model_cost


def as_pair(report, name, tableau, on_group, family):
    """A copy of one method's runs under another name: a user's tableau pair."""
    out = []
    for r in report["runs"]:
        if r["integrator"] == name:
            x = copy.deepcopy(r)
            x.update(integrator=f"{'rkmk' if on_group else 'rk'}-{tableau}", tableau=tableau, on_group=on_group,
                     family=family)
            out.append(x)
    return out


class Findings(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = syn.make_report()
        cls.markdown = summary.summary_markdown(cls.report)

    def test_findings_come_first(self):
        lines = self.markdown.splitlines()
        self.assertEqual(lines[0], "# rollbench summary")
        self.assertEqual(next(line for line in lines if line.startswith("## ")), findings.HEADING)
        self.assertEqual(sum(1 for line in lines if line == summary.CONTENTS), 1)
        self.assertLess(lines.index(findings.HEADING), lines.index(summary.CONTENTS))

    def test_scene_kind_comes_from_the_report(self):
        rows = {r[0]: r for r in md.parse_table(self.markdown, "### Cheapest method by wall time")}
        self.assertEqual(rows["plane"][1], "homogeneous")
        self.assertEqual(rows["valley-sideways"][1], "R feeds back (moments 0.0025, 0.004, 0.0055 kg m²)")

    def test_cheapest_follows_the_model(self):
        rows = {r[0]: r for r in md.parse_table(self.markdown, "### Cheapest method by wall time")}
        for scene in syn.SCENES:
            for cell, target in zip(rows[scene][2:], costs.TARGETS):
                # the findings read error_max: the target for the error at t_end is smaller
                found = {n: model_cost(scene, n, "time", target / syn.ERROR_MAX_FACTOR)
                         for n in list(syn.FIXED) + list(syn.ADAPTIVE)}
                (cost, bound), name = min((c, n) for n, c in found.items() if math.isfinite(c[0]))
                with self.subTest(scene=scene, target=target):
                    self.assertTrue(cell.startswith(name + " ("), cell)
                    self.assertTrue(math.isclose(md.as_number(cell.split("(")[1].split(" s)")[0]), cost,
                                                 rel_tol=REL))

    def test_pairs_come_from_the_tableau_facts(self):
        report = syn.make_report()
        self.assertEqual({(f, lie) for f, lie, _ in pairs.tableau_pairs(rp.runs(report))}, set(syn.PAIRS))
        # a method without a tableau is in no pair, whatever its name says
        for r in report["runs"]:
            if r["integrator"] == "rkmk8":
                r["tableau"] = None
        self.assertNotIn(("odeint-fehlberg78", "rkmk8"),
                         {(f, lie) for f, lie, _ in pairs.tableau_pairs(rp.runs(report))})

    def test_a_user_tableau_pair_is_paired(self):
        report = syn.make_report()
        report["runs"] += as_pair(report, "rk4", "mine", False, "rk") + as_pair(report, "rkmk4", "mine", True, "rkmk")
        self.assertIn(("rk-mine", "rkmk-mine", "mine"), pairs.tableau_pairs(rp.runs(report)))
        text = summary.summary_markdown(report)
        table = md.parse_table(text, "### Same tableau: flat / Lie time ratio")
        rows = [r for r in table if r[2] == "rk-mine / rkmk-mine"]
        self.assertEqual(len(rows), len(syn.SCENES))
        self.assertTrue(all(r[3] == "mine" for r in rows))

    def test_ratios_follow_the_model_with_their_spread(self):
        rows = md.parse_table(self.markdown, "### Same tableau: flat / Lie time ratio")
        self.assertEqual(len(rows), len(syn.SCENES) * len(syn.PAIRS))
        for scene, kind, pair, _, *cells in rows:
            flat, lie = pair.split(" / ")
            self.assertEqual(kind, "R feeds back" if scene in syn.INERTIA else "homogeneous")
            for cell, target in zip(cells, costs.TARGETS):
                a, bound_a = model_cost(scene, flat, "time", target / syn.ERROR_MAX_FACTOR)
                b, bound_b = model_cost(scene, lie, "time", target / syn.ERROR_MAX_FACTOR)
                with self.subTest(scene=scene, pair=pair, target=target):
                    if not (math.isfinite(a) and math.isfinite(b)):
                        self.assertEqual(cell, "—")
                        continue
                    # every sample is the median times the same factor for both: no spread
                    value = md.as_number(cell.replace("≥", "").replace("~", "").split(" [")[0])
                    self.assertTrue(math.isclose(value, a / b, rel_tol=REL), f"{cell} != {a / b:.3g}")
                    low, high = (float(x) for x in cell.split("[")[1].rstrip("]").split("–"))
                    self.assertTrue(math.isclose(low, high, rel_tol=REL))
                    self.assertEqual(cell.startswith("≤"), bool(bound_a) and not bound_b)

    def test_spread_is_the_timing_over_repeats(self):
        report = copy.deepcopy(self.report)
        for r in report["runs"]:
            if r["integrator"] == "rkmk4":
                r["wall_s"]["samples"] = [s * f for s, f in zip(r["wall_s"]["samples"], (1, 2, 1, 1, 1))]
        runs = rp.runs(report, "plane")
        median, low, high, repeats, _ = pairs.time_ratio(runs, "rk4", "rkmk4", "worst", 0.0, 1e-6)
        a, _ = model_cost("plane", "rk4", "time", 1e-6)
        b, _ = model_cost("plane", "rkmk4", "time", 1e-6)
        self.assertEqual(repeats, len(syn.SAMPLE_SPREAD))
        self.assertTrue(math.isclose(high, a / b, rel_tol=REL))
        # repeat 1: rkmk4 twice as slow, its ratio half
        self.assertTrue(math.isclose(low, 0.5 * a / b, rel_tol=REL))
        self.assertTrue(math.isclose(median, a / b, rel_tol=REL))

    def test_answer_lines_count_where_the_lie_method_pays(self):
        text = "\n".join(findings.findings_section(self.report))
        self.assertIn("- Keeping R on SO(3) where R feeds back: the Lie method is cheaper in", text)
        self.assertIn("- Keeping R on SO(3) on homogeneous scenes:", text)

    def test_verdict_counts_and_reasons(self):
        report = copy.deepcopy(self.report)
        for o in report["orders"]:
            if (o["scene"], o["integrator"]) == ("plane", "rkmk8"):
                o["inconclusive_reason"] = {"contact": "floor", "centre": "floor", "omega": "wide interval",
                                            "rotation": "too few points"}
            if (o["scene"], o["integrator"]) == ("plane", "rk4"):
                # every step on the plateau: no slope, a verdict
                o["verdict"]["omega"] = "exact"
                o["observed"]["omega"] = None
        text = "\n".join(findings.findings_section(report))
        total = len(syn.SCENES) * len(syn.FIXED) * 4
        self.assertIn(f"- Orders: {total - 4} of {total} component fits reach a verdict ({total - 9} as declared, "
                      "4 lower, 1 exact); 4 are inconclusive (2 floor, 1 too few points, 1 wide interval)", text)
        # the synthetic report's gsl-rk4 reads one order low on valley-sideways
        self.assertIn("- `lower` verdicts: 4 components: gsl-rk4 on valley-sideways (contact 3 of 4, centre 3 of 4, "
                      "omega 3 of 4, rotation 3 of 4).", text)

    def test_lower_verdicts_are_counted_and_named(self):
        report = copy.deepcopy(self.report)
        for o in report["orders"]:
            if (o["scene"], o["integrator"]) == ("plane", "rkmk8"):
                o["verdict"]["rotation"] = "lower"
                o["observed"]["rotation"] = 5.123
        text = "\n".join(findings.findings_section(report))
        self.assertIn("- `lower` verdicts: 5 components: rkmk8 on plane (rotation 5.12 of 8); gsl-rk4 on", text)

    def test_best_of_family_is_the_cheapest_over_the_range(self):
        # b has the most points on the family's front, a is cheaper over the accuracy range
        runs = [rp.Run.of({"scene": "plane", "integrator": n, "adaptive": False, "status": "ok", "rhs_evals": c,
                           "error": {"worst": e}})
                for n, c, e in (("a", 10, 1e-2), ("a", 100, 1e-7), ("b", 11, 5e-3), ("b", 12, 2e-3),
                                ("b", 13, 1e-3), ("b", 5000, 1e-7))]
        front = figures_precision.pareto_front([(r.rhs_evals, rp.error(r)) for r in runs])
        self.assertGreater(sum(1 for i in front if runs[i].integrator == "b"), 1)
        pick = figures_precision.best_of_family(runs, ["b", "a"], lambda r: r.rhs_evals, "worst", 0.0)
        self.assertEqual(pick, "a")


class EitherError(unittest.TestCase):
    def test_the_tables_can_read_error_max(self):
        from analysis import report as rp
        report = syn.make_report()
        try:
            rp.use_errors("max")
            text = summary.summary_markdown(report)
        finally:
            rp.use_errors("end")
        self.assertIn("read from each run's `error_max`", text)
        # error_max is 1.5 x error in the model: the cost to 1e-6 at 1.5 e-6 of the error
        rows = {r[0]: r for r in md.parse_table(text, "### Cost to accuracy — plane")}
        a, _ = model_cost("plane", "rkmk4", "rhs", 1e-6 / 1.5)
        self.assertTrue(math.isclose(md.as_number(rows["rkmk4"][3]), a, rel_tol=REL))


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROLLBENCH = os.environ.get("RB_ROLLBENCH", os.path.join(ROOT, "build", "release", "rollbench"))


@unittest.skipUnless(os.path.exists(ROLLBENCH), "no rollbench binary (RB_ROLLBENCH)")
class UserTableauEndToEnd(unittest.TestCase):
    def test_a_tableau_file_gives_a_pair_in_the_findings(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "r.json")
            done = subprocess.run([ROLLBENCH, "run", "--preset", "quick", "--no-stability", "--scenes",
                                   "plane,chaplygin-valley", "--tableau",
                                   os.path.join(ROOT, "examples", "tableaux", "ralston3.json"), "--integrators",
                                   "rk-ralston3,rkmk-ralston3", "--h", "2^-5..2^-12", "--repeats", "2", "--out", out],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out, encoding="utf-8") as f:
                report = json.load(f)
        text = summary.summary_markdown(report)
        rows = {(r[0], r[2]): r for r in md.parse_table(text, "### Same tableau: flat / Lie time ratio")}
        self.assertEqual(set(rows), {("plane", "rk-ralston3 / rkmk-ralston3"),
                                     ("chaplygin-valley", "rk-ralston3 / rkmk-ralston3")})
        self.assertEqual(rows[("chaplygin-valley", "rk-ralston3 / rkmk-ralston3")][1], "R feeds back")
        self.assertEqual(rows[("plane", "rk-ralston3 / rkmk-ralston3")][1], "homogeneous")
        self.assertEqual(rows[("plane", "rk-ralston3 / rkmk-ralston3")][3], "ralston3")


if __name__ == "__main__":
    unittest.main()


class Aggregates(unittest.TestCase):
    """Bounds and exact scenes stay out of the counts; each Lie method counts once, against its cheapest twin."""

    def setUp(self):
        self.report = syn.make_report()

    def answer(self, report, where="where R feeds back"):
        text = "\n".join(findings.findings_section(report))
        line = next(x for x in text.splitlines() if x.startswith(f"- Keeping R on SO(3) {where}"))
        return text, int(line.split(" of ")[1].split()[0])

    def expected_count(self, report, feeds):
        """Cells with a measured (unbounded) ratio, one per Lie method and target, from pairs.time_ratio."""
        n = 0
        with findings.rp.errors_read("max"):
            for scene in syn.SCENES:
                if (scene in syn.INERTIA) != feeds:
                    continue
                for _, _, _, ratios in findings.pair_ratios(report, scene, "worst"):
                    n += sum(1 for t in costs.TARGETS if math.isfinite(ratios[t][0]) and not ratios[t][4])
        return n

    def test_bounds_are_listed_apart(self):
        text, count = self.answer(self.report)
        self.assertEqual(count, self.expected_count(self.report, True))
        with findings.rp.errors_read("max"):
            ratios = findings.pair_ratios(self.report, "valley-sideways", "worst")
        bounds = [(f, lie, t) for f, lie, _, r in ratios for t in costs.TARGETS if r[t][4]]
        self.assertTrue(bounds, "the synthetic report should hold a bounded ratio")
        for flat, lie, t in bounds:
            self.assertIn(f"valley-sideways {flat} / {lie} at {t:.0e}: ", text)

    def test_a_costlier_variant_is_marked_and_not_counted(self):
        report = copy.deepcopy(self.report)
        twin = as_pair(report, "rk4", "rk4", False, "rk")
        for r in twin:
            r["integrator"] = "rk4-slow-variant"
            r["wall_s"] = {k: (v * 3 if isinstance(v, float) else [x * 3 for x in v] if isinstance(v, list) else v)
                           for k, v in r["wall_s"].items()}
        report["runs"] += twin
        _, count = self.answer(report)
        self.assertEqual(count, self.expected_count(self.report, True))
        rows = md.parse_table("\n".join(findings.findings_section(report)), "### Same tableau: flat / Lie time ratio")
        self.assertIn("rk4-slow-variant / rkmk4 (variant)", [r[2] for r in rows])
        self.assertIn("rk4 / rkmk4", [r[2] for r in rows])

    def test_a_cheaper_library_method_with_the_tableau_is_a_variant_not_the_pair(self):
        # odeint's dopri5 beside rkmk-dp54-adaptive: the same tableau, but its own norm and controller; the
        # counted pair is the suite's own flat twin even where the library's method is cheaper
        report = copy.deepcopy(self.report)
        library = as_pair(report, "rk4", "rk4", False, "odeint")
        for r in library:
            r["integrator"] = "odeint-rk4-fast"
            r["wall_s"] = {k: (v / 3 if isinstance(v, float) else [x / 3 for x in v] if isinstance(v, list) else v)
                           for k, v in r["wall_s"].items()}
        report["runs"] += library
        _, count = self.answer(report)
        self.assertEqual(count, self.expected_count(self.report, True))
        rows = md.parse_table("\n".join(findings.findings_section(report)), "### Same tableau: flat / Lie time ratio")
        self.assertIn("odeint-rk4-fast / rkmk4 (variant)", [r[2] for r in rows])
        self.assertIn("rk4 / rkmk4", [r[2] for r in rows])
        # with no twin of its own (only the library's method shares the tableau), the library's method is the pair
        alone = copy.deepcopy(report)
        alone["runs"] = [r for r in alone["runs"] if r["integrator"] != "rk4"]
        rows = md.parse_table("\n".join(findings.findings_section(alone)), "### Same tableau: flat / Lie time ratio")
        self.assertIn("odeint-rk4-fast / rkmk4", [r[2] for r in rows])

    def test_an_exact_method_is_named_and_left_out(self):
        report = copy.deepcopy(self.report)
        for r in report["runs"]:
            if r["scene"] == "plane" and r["integrator"] == "rkmk4" and r["status"] == "ok":
                r["error_max"]["below_floor"] = list(syn.COMPONENTS) + ["worst"]
        text, count = self.answer(report, "on homogeneous scenes")
        self.assertIn("- Exact (every run at the reference floor; left out of the counts): rkmk4 on plane.", text)
        _, before = self.answer(self.report, "on homogeneous scenes")
        with findings.rp.errors_read("max"):
            rk4 = [r for f, lie, _, r in findings.pair_ratios(self.report, "plane", "worst") if lie == "rkmk4"][0]
        self.assertEqual(count, before - sum(1 for t in costs.TARGETS if math.isfinite(rk4[t][0]) and not rk4[t][4]))

    def test_one_line_per_scene_where_r_feeds_back(self):
        text, count = self.answer(self.report)
        line = next(x for x in text.splitlines() if x.startswith("  - valley-sideways: "))
        self.assertIn(f" of {count} pair × target cells", line)
        self.assertNotIn("  - plane: ", text)

"""The regime map against a hand-made report whose answers are known: every
method's work-precision curve has errors 1e-2, 1e-4, ..., 1e-10 at costs
c × 1, 2, 4, 8, 16, so it reaches 1e-4 at 2c, 1e-6 at 4c and 1e-9 at
sqrt(8 × 16) c; flat methods' timed repeats are c × (1, 0.9, 1.2), Lie ones'
c × 1, so a pair's ratio is c_flat / c_Lie with the spread [0.9, 1.2] × it.
A pair is a Lie method and its geometry twin (the same tableau, controller
and norm): odeint's dopri5 is cheaper than the suite's rk-dp54-adaptive in
both cells, and never the pair's flat side."""
import math
import os
import tempfile
import unittest

from analysis import findings, html, plot, regime, summary
from analysis import markdown as md
from analysis import report as rp

ERRORS = (1e-2, 1e-4, 1e-6, 1e-8, 1e-10)
STEPS = (1, 2, 4, 8, 16)
FLAT_SPREAD = (1.0, 0.9, 1.2)
# name: declared order, on the group, adaptive, tableau, family, controller (the report's MethodInfo facts)
METHODS = {"rk4": (4, False, False, "rk4", "rk", "constant"),
           "rk4-projected": (4, False, False, "rk4", "projected", "constant"),
           "rkmk4": (4, True, False, "rk4", "rkmk", "constant"),
           "rk-dp54-adaptive": (5, False, True, "dp54", "rk", "pi"),
           "odeint-dopri5-adaptive": (5, False, True, "dp54", "odeint", "library"),
           "rkmk-dp54-adaptive": (5, True, True, "dp54", "rkmk", "pi")}
# per cell: {method: c}; the homogeneous cell's winner is flat, the other's a Lie method
CELLS = {
    "regime-i1-s5-r0-t1": (1.0, {"rk4": 1.0, "rk4-projected": 1.5, "rkmk4": 2.0, "rk-dp54-adaptive": 0.9,
                                 "odeint-dopri5-adaptive": 0.8, "rkmk-dp54-adaptive": 1.8}),
    "regime-i3-s5-r0-t1": (3.0, {"rk4": 3.0, "rk4-projected": 2.5, "rkmk4": 1.0, "rk-dp54-adaptive": 3.0,
                                 "odeint-dopri5-adaptive": 2.8, "rkmk-dp54-adaptive": 2.0}),
}
# rkmk4 in the anisotropic cell stops short of 1e-9 (its last run is missing)
SHORT = ("regime-i3-s5-r0-t1", "rkmk4")


def make_runs(scene, costs):
    runs = []
    for name, c in costs.items():
        order, on_group, adaptive, tableau, family, controller = METHODS[name]
        for k, (e, steps) in enumerate(zip(ERRORS, STEPS)):
            if (scene, name) == SHORT and k == len(ERRORS) - 1:
                continue
            samples = [c * steps * (s if not on_group else 1.0) for s in FLAT_SPREAD]
            runs.append({"scene": scene, "integrator": name, "family": family, "tableau": tableau,
                         "controller": controller,
                         "adaptive": adaptive, "status": "ok", "declared_order": order, "on_group": on_group,
                         "h": None if adaptive else 2.0 ** -k, "rtol": 10.0 ** -k if adaptive else None,
                         "rhs_evals": 100 * steps,
                         "wall_s": {"median": sorted(samples)[1], "samples": samples, "repeats": 3},
                         "error": {"worst": e, "below_floor": []},
                         "error_max": {"worst": e, "below_floor": []}})  # the findings read the worst over the run
    return runs


def make_report():
    runs, refs, cells = [], [], []
    for scene, (inertia, costs) in CELLS.items():
        runs += make_runs(scene, costs)
        refs.append({"scene": scene, "error": 1e-14, "r_feeds_back": inertia > 1,
                     "inertia": [0.002, 0.004, 0.006] if inertia > 1 else None})
        cells.append({"scene": scene, "inertia": inertia, "spin": 5.0, "roughness": 0.0, "t_end": 1.0})
    return {"schema": "rollbench.report/2", "runs": runs, "references": refs,
            "regime": {"axes": {"inertia": [1.0, 3.0], "spin": [5.0], "roughness": [0.0], "t_end": [1.0]},
                       "cells": cells}}


def at(target, c):
    """The cost at which a curve of constant c reaches the target."""
    return {1e-4: 2 * c, 1e-6: 4 * c, 1e-9: math.sqrt(8 * 16) * c}[target]


class RegimeMap(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = make_report()
        cls.results = regime.regime_results(cls.report)

    def test_cheapest_method_and_the_best_twin_pair(self):
        homogeneous, anisotropic = CELLS
        for target in regime.TARGETS:
            with self.subTest(target=target):
                r = self.results[(homogeneous, target)]
                self.assertEqual(r["winner"][0], "odeint-dopri5-adaptive")
                self.assertFalse(r["on_group"])
                self.assertAlmostEqual(r["winner"][1], at(target, 0.8))
                # rk4's tableau: the cheaper twin is rk4 (1), not rk4-projected (1.5), against rkmk4 (2)
                by_tableau = {p[0]: p for p in r["pairs"]}
                self.assertEqual(set(by_tableau), {"rk4", "dp54"})
                self.assertEqual(by_tableau["rk4"][1:3], ("rk4", "rkmk4"))
                self.assertAlmostEqual(by_tableau["rk4"][3][0], 0.5)
                # the headline: dp54's, whose cheaper side (0.9) is the cheapest; its flat side the suite's
                # rk-dp54-adaptive, not odeint's dopri5 (0.8, the cheapest method), whose controller is its own
                tableau, flat, lie, ratio = r["pair"]
                self.assertEqual((tableau, flat, lie), ("dp54", "rk-dp54-adaptive", "rkmk-dp54-adaptive"))
                self.assertAlmostEqual(ratio[0], 0.5)
                self.assertAlmostEqual(ratio[1], 0.5 * 0.9)
                self.assertAlmostEqual(ratio[2], 0.5 * 1.2)
        for target in (1e-4, 1e-6):
            r = self.results[(anisotropic, target)]
            self.assertEqual(r["winner"][0], "rkmk4")
            self.assertTrue(r["on_group"])
            # rk4's tableau: rk4-projected (2.5) is the cheaper of rkmk4's two twins
            self.assertEqual(r["pair"][:3], ("rk4", "rk4-projected", "rkmk4"))
            self.assertAlmostEqual(r["pair"][3][0], 2.5)
        # at 1e-9 rkmk4 is not there: no rk4 pair; the winner and the pair are dp54's, against rk-dp54-adaptive
        # (3), not the cheaper odeint-dopri5-adaptive (2.8)
        r = self.results[(anisotropic, 1e-9)]
        self.assertEqual(r["winner"][0], "rkmk-dp54-adaptive")
        self.assertEqual([p[:3] for p in r["pairs"]], [("dp54", "rk-dp54-adaptive", "rkmk-dp54-adaptive")])
        self.assertAlmostEqual(r["pair"][3][0], 1.5)

    def test_without_a_twin_the_library_method_stands_in(self):
        # an older report: odeint's dopri5 and no rk-dp54-adaptive; the pair is odeint's, as the findings' is
        report = make_report()
        report["runs"] = [r for r in report["runs"] if r["integrator"] != "rk-dp54-adaptive"]
        r = regime.cell_result(report, "regime-i3-s5-r0-t1", 1e-9)
        self.assertEqual(r["pair"][:3], ("dp54", "odeint-dopri5-adaptive", "rkmk-dp54-adaptive"))
        self.assertAlmostEqual(r["pair"][3][0], 1.4)

    def test_the_regime_map_and_the_findings_pair_alike(self):
        # each Lie method of the findings' aggregate is paired with the flat method the regime map pairs it with
        for scene in CELLS:
            with rp.errors_read("max"):
                cells, *_ = findings.aggregate_cells(self.report, scene, "worst",
                                                     findings.pair_ratios(self.report, scene, "worst"))
            for lie, flat, target, _ in cells:
                if target in regime.TARGETS:
                    pairs = {p[2]: p[1] for p in self.results[(scene, target)]["pairs"]}
                    self.assertEqual(pairs[lie], flat, (scene, target))

    def test_summary_section_has_a_table_per_target(self):
        text = summary.summary_markdown(self.report)
        for target in regime.TARGETS:
            rows = md.parse_table(text, f"### Regime map at worst error {target:.0e}")
            self.assertEqual([r[:4] for r in rows], [["1", "5", "0", "1"], ["3", "5", "0", "1"]])
            # an older grid's report: no bowl, speed or rates
            self.assertEqual(rows[1][4:7], ["—", "—", "—"])
            self.assertTrue(rows[1][7].startswith("rkmk4 (" if target != 1e-9 else "rkmk-dp54-adaptive ("), rows[1])
        rows = md.parse_table(text, "### Regime map at worst error 1e-06")
        self.assertEqual(rows[1][8:], ["rk4: rk4-projected / rkmk4", "2.50 [2.25–3.00]"])
        self.assertEqual(rows[0][8:], ["dp54: rk-dp54-adaptive / rkmk-dp54-adaptive", "0.50 [0.45–0.60]"])

    def test_the_findings_line(self):
        lines = findings.findings_section(self.report)
        line = next(x for x in lines if x.startswith("- Regime map"))
        self.assertEqual(line, "- Regime map (2 generated scenes × worst error 1e-04, 1e-06, 1e-09, figures "
                               "regime-<target>.png): where R feeds back (inertia ratio > 1) the Lie side of the best "
                               "twin pair is cheaper in 3, the flat side in 0, and 0 are ties (the repeats' "
                               "range holds 1) of 3 measured cell × target, flat/Lie 1.50 to 2.50 (median 2.50); on "
                               "the homogeneous ball the Lie side of the best twin pair is cheaper in 0, the "
                               "flat side in 3, and 0 are ties (the repeats' range holds 1) of 3 measured cell × "
                               "target, flat/Lie 0.50 to 0.50 (median 0.50). Cheapest method most "
                               "often (of 6 cell × target): odeint-dopri5-adaptive 3, rkmk4 2, rkmk-dp54-adaptive 1; 0 "
                               "reached by none.")
        # the cells lack the rates (an older report): no border to fit
        self.assertIn("- Regime border: no crossover to fit: under two decided cells where R feeds back, or one side "
                      "wins them all.", lines)

    def test_a_report_without_a_regime_section_has_none(self):
        plain = make_report()
        del plain["regime"]
        self.assertEqual(regime.regime_section(plain), [])
        self.assertEqual(regime.findings_lines(plain), [])
        self.assertNotIn(regime.HEADING, summary.summary_markdown(plain))

    def test_heat_maps_mark_the_lie_winners(self):
        fig = regime.heat_map(self.report, 1e-6, results=self.results)
        ax = fig.axes[0]
        texts = sorted(t.get_text() for t in ax.texts)
        self.assertEqual(texts, ["0.5\ndopri5 (a)", "2.5\nrkmk4"])
        # one marker: the anisotropic cell, whose cheapest is a Lie-group method
        self.assertEqual(len(ax.lines), 1)
        self.assertEqual(tuple(ax.lines[0].get_xydata()[0]), (0.36, 1.32))

    def test_plot_writes_the_figures_into_the_findings(self):
        with tempfile.TemporaryDirectory() as out:
            written = [os.path.basename(p) for p in plot.write_all(self.report, out, log=lambda _: None)]
            for target in regime.TARGETS:
                self.assertIn(regime.figure_name(target), written)
            with open(os.path.join(out, "index.html"), encoding="utf-8") as f:
                page = f.read()
        # inside the findings, after its lines and before its tables
        lines_end = page.index("</ul>", page.index('<h2 id="findings">'))
        tables = page.index('<h3 id="cheapest-method-by-wall-time">')
        for target in regime.TARGETS:
            self.assertLess(lines_end, page.index(f'src="{regime.figure_name(target)}"'))
            self.assertLess(page.index(f'src="{regime.figure_name(target)}"'), tables)
        self.assertTrue(html.FINDINGS_FIGURES)


if __name__ == "__main__":
    unittest.main()

"""The regime map's border on a hand-made report whose answers are known:
seven cells where R feeds back, with |ω0|/Ω = 0.25 … 16 and rk4 / rkmk4
time ratio sqrt(X / 2); rk4's timed repeats spread by (1, 0.9, 1.2)
(test_regime.make_runs), so a cell whose ratio lies in [1/1.2, 1/0.9] is a
tie: X = 2 is, and the decided ones lie symmetric about it on a log scale,
flat below, Lie above, so the crossover is X = 2 exactly. Four held-out scenes: two the rule gets right,
one it gets wrong and one tie."""
import math
import os
import tempfile
import unittest

from analysis import crossover, findings, plot, regime, summary
from analysis import markdown as md
from tests.analysis.test_regime import make_runs

XS = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)
# held out: (name, kind, omega0, bowl_frequency, flat/Lie ratio)
HELD_OUT = (("regime-offgrid-a", "off-grid", 0.3, 1.0, 0.6),   # flat predicted, flat measured
            ("chaplygin-plane", "shipped", 8.0, 0.0, 3.0),     # X = ∞: Lie, Lie
            ("regime-offgrid-b", "off-grid", 5.0, 1.0, 0.5),   # Lie predicted, flat measured: wrong
            ("regime-offgrid-c", "off-grid", 1.9, 1.0, 1.0))   # a tie: not counted


def border_report():
    runs, refs, cells, held = [], [], [], []
    for i, x in enumerate(XS):
        scene = f"regime-i3-s{i}"
        runs += make_runs(scene, {"rk4": math.sqrt(x / 2), "rkmk4": 1.0})
        refs.append({"scene": scene, "error": 1e-14, "r_feeds_back": True, "inertia": [0.002, 0.004, 0.006]})
        cells.append({"scene": scene, "inertia": 3.0, "spin": float(i), "roughness": 0.0, "t_end": 1.0,
                      "bowl": 0.5, "speed": 0.1, "omega0": x, "bowl_frequency": 1.0})
    for name, kind, omega0, frequency, ratio in HELD_OUT:
        runs += make_runs(name, {"rk4": ratio, "rkmk4": 1.0})
        refs.append({"scene": name, "error": 1e-14, "r_feeds_back": True, "inertia": [0.002, 0.004, 0.006]})
        held.append({"scene": name, "kind": kind, "omega0": omega0, "bowl_frequency": frequency})
    return {"schema": "rollbench.report/2", "runs": runs, "references": refs,
            "regime": {"axes": {"inertia": [3.0], "spin": [float(i) for i in range(len(XS))], "roughness": [0.0],
                                "t_end": [1.0], "bowl": [0.5], "speed": [0.1], "held_out": True},
                       "cells": cells, "held_out": held}}


class RegimeBorder(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = border_report()
        cls.results = regime.regime_results(cls.report)

    def test_the_crossover_is_where_the_ratio_was_made_to_cross(self):
        fit = regime.border(self.report, self.results)
        self.assertAlmostEqual(fit["x_star"], 2.0, places=9)
        self.assertGreater(fit["slope"], 0)
        self.assertEqual((fit["cells"], fit["points"]), (6, 18))  # the tie's cell is left out
        self.assertLess(fit["low"], 2.0)
        self.assertGreater(fit["high"], 2.0)
        self.assertLess(fit["low"], 1.0)  # within the gap between the sides, 1 to 4
        self.assertGreater(fit["high"], 1.0)

    def test_ties_flat_wins_and_the_held_out_check(self):
        # X = 2: ratio 1, its range [0.9, 1.2] holds 1
        self.assertEqual(crossover.outcome(regime._ratio(self.results[("regime-i3-s3", 1e-6)])), crossover.TIE)
        flat = regime.flat_wins(self.report, self.results)
        self.assertEqual(sorted({s for s, _, _ in flat}), ["regime-i3-s0", "regime-i3-s1", "regime-i3-s2"])
        self.assertEqual(len(flat), 9)
        rows = regime.held_out_rows(self.report, self.results, regime.border(self.report, self.results))
        self.assertEqual(len(rows), 12)
        by_scene = {r[0]["scene"]: r for r in rows if r[1] == 1e-6}
        self.assertEqual([by_scene[n][3:6] for n, *_ in HELD_OUT],
                         [(crossover.FLAT, crossover.FLAT, True), (crossover.LIE, crossover.LIE, True),
                          (crossover.LIE, crossover.FLAT, False), (crossover.FLAT, crossover.TIE, None)])

    def test_the_findings_lines(self):
        lines = findings.findings_section(self.report)
        line = next(x for x in lines if x.startswith("- Regime map"))
        self.assertIn("the Lie side of the best twin pair is cheaper in 9, the flat side in 9, and 3 are ties "
                      "(the repeats' range holds 1) of 21 measured cell × target", line)
        fit = regime.border(self.report, self.results)
        self.assertIn(f"- Regime border: the Lie method pays where |ω0|/Ω > 2 [{fit['low']:.2g}–{fit['high']:.2g}], "
                      "|ω0| the ball's rotation rate and Ω the bowl's frequency at the start (logistic fit of the Lie "
                      "side winning on log |ω0|/Ω over 18 decided cell × target (6 cells) where R feeds back, slope "
                      f"{fit['slope']:.2f} per decade; 95 % interval from resampling the cells; figure "
                      "regime-border.png).", lines)
        flat = next(x for x in lines if x.startswith("- Flat wins"))
        self.assertTrue(flat.startswith("- Flat wins (beyond the timing's noise) in 9 grid cell × target: "
                                        "regime-i3-s0 at 1e-04 (0.35 [0.32–0.42])"), flat)
        held = next(x for x in lines if x.startswith("- Held out"))
        self.assertEqual(held, "- Held out (4 scenes not fitted on × 3 targets): the rule predicts the winner in 6 "
                               "of 9 decided (67%); 3 ties and 0 without a measured ratio not counted. Wrong: "
                               "regime-offgrid-b at 1e-04 (|ω0|/Ω 5: predicted Lie, measured flat); regime-offgrid-b "
                               "at 1e-06 (|ω0|/Ω 5: predicted Lie, measured flat); regime-offgrid-b at 1e-09 (|ω0|/Ω "
                               "5: predicted Lie, measured flat).")

    def test_the_summary_tables_the_held_out_scenes(self):
        text = summary.summary_markdown(self.report)
        rows = md.parse_table(text, "### Held-out scenes")
        self.assertEqual(len(rows), 12)
        plane = next(r for r in rows if r[0] == "chaplygin-plane (shipped)" and r[1] == "1e-06")
        self.assertEqual(plane, ["chaplygin-plane (shipped)", "1e-06", "∞", "Lie", "Lie", "3.00 [2.70–3.60]",
                                 "yes"])
        rows = md.parse_table(text, "### Regime map at worst error 1e-06")
        self.assertEqual([r[6] for r in rows], ["0.25", "0.5", "1", "2", "4", "8", "16"])

    def test_a_falling_ratio_states_no_crossover(self):
        report = border_report()
        for cell in report["regime"]["cells"]:
            cell["omega0"] = 1.0 / cell["omega0"]  # the same ratios, now falling with X
        lines = regime.border_lines(report, regime.regime_results(report))
        self.assertTrue(lines[0].startswith("- Regime border: no crossover: the Lie side does not win more often as "
                                            "|ω0|/Ω grows"), lines[0])

    def test_the_border_figure_is_written(self):
        with tempfile.TemporaryDirectory() as out:
            written = [os.path.basename(p) for p in plot.write_all(self.report, out, log=lambda _: None)]
        self.assertIn(regime.BORDER_FIGURE, written)
        fig = regime.border_figure(self.report, results=self.results)
        self.assertEqual(fig.axes[0].get_xscale(), "log")


if __name__ == "__main__":
    unittest.main()

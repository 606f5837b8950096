"""The stability study's two limits as the analysis shows them (analysis/stability.py): the summary's table and the
findings' lines name the blow-up step and h*(T) per horizon with the quantity that crossed, the figure draws both,
the schema checks the new keys, and a report written before them keeps its old table and figure."""
import copy
import json
import unittest

import matplotlib

matplotlib.use("Agg")

from analysis import figures_overview, findings, stability, style, summary  # noqa: E402
from analysis import markdown as md  # noqa: E402
from analysis import report as rp  # noqa: E402
from tests.analysis import synthetic as syn  # noqa: E402

HORIZONS = [10.0, 100.0, 1000.0]
BOUNDS = {"energy": 0.1, "rotation_defect": 0.5, "blow_up_energy": 10.0, "blow_up_defect": 10.0,
          "blow_up_steps": 10, "growth_exponent": 3.0, "growth_floor": 1e-9}


def drift(h, limited_by, next_h, value=None, bound=None, blow_up=None, at_limit=False):
    return {"h": h, "at_limit": at_limit, "next_h": next_h, "limited_by": limited_by, "blow_up": blow_up,
            "value": value, "bound": bound}


# (blow-up steps per horizon with cause and status, drift-limited steps per horizon)
LIMITS = {
    # a flat method: R leaves SO(3) as a power of t, h* falls a rung a decade; blow-up the same
    "rk4": ([(0.5, "defect-blow-up", "ok")] * 3,
            [drift(0.0625, "rotation-defect", 0.125, 0.71, 0.5), drift(0.03125, "rotation-defect", 0.0625, 1.02, 0.5),
             drift(0.015625, "rotation-defect", 0.03125, 0.51, 0.5)]),
    # a Lie method limited by its energy drift (cf4 at h = 1: 45 % off at 10 s is outside the bound)
    "rkmk4": ([(4.0, "stopped", "chart-limit")] * 3,
              [drift(0.5, "energy", 1.0, 0.45, 0.1), drift(0.25, "energy", 0.5, 0.19, 0.1),
               drift(0.25, "energy", 0.5, 1.03, 0.1)]),
    # every step tried blows up: h* none, the blow-up step at most the smallest step tried
    "euler": ([(0.0009765625, "stopped", "domain")] * 3,
              [dict(drift(None, "blow-up", 0.0009765625, blow_up="stopped"), status="domain")] * 3),
    # a step that fails only late (the exponential chart's edge at 23 s): the blow-up step moves a rung
    "rkmk4-seminar": ([(1.0, "stopped", "chart-limit"), (0.5, "stopped", "chart-limit"),
                       (0.5, "stopped", "chart-limit")],
                      [drift(0.25, "energy", 0.5, 0.1004, 0.1), drift(0.25, "blow-up", 0.5, blow_up="stopped"),
                       drift(0.25, "blow-up", 0.5, blow_up="stopped")]),
}


def entry(scene, name):
    blow, limited = LIMITS[name]
    tried = [{"h": x, "status": "ok", "stable": False, "failure": "energy"} for x in (0.0009765625, 0.5, 1.0)]
    return {"scene": scene, "integrator": name, "family": syn.FIXED[name][0], "h": limited[-1]["h"],
            "horizon": 1000.0, "horizons": HORIZONS, "at_limit": False, "thresholds": BOUNDS, "tried": tried,
            "blow_up": {"same_at_every_horizon": len({b[0] for b in blow}) == 1,
                        "at": [{"horizon": t, "h": h, "cause": cause, "status": status,
                                "smallest_tried": h == 0.0009765625}
                               for t, (h, cause, status) in zip(HORIZONS, blow)]},
            "drift_limited": [dict(d, horizon=t) for t, d in zip(HORIZONS, limited)]}


def report_with_limits():
    report = syn.make_report()
    report["stability"]["largest_stable_h"] = [entry(scene, name) for scene in ("bumpy-long", "bowl-3d")
                                               for name in LIMITS]
    return rp.validate(json.loads(json.dumps(report)))


class Limits(unittest.TestCase):
    def setUp(self):
        self.report = report_with_limits()

    def test_the_summary_names_both_limits_and_what_crossed(self):
        text = "\n".join(summary.stability_section(self.report))
        rows = {(r[0], r[1]): r for r in md.parse_table(text, "## Stability")}
        self.assertEqual(len(rows), 8)
        rk4 = rows[("bumpy-long", "rk4")]
        self.assertEqual(rk4[2], "0.5 (defect-blow-up)")
        self.assertEqual(rk4[3], "0.0625 (rotation defect 0.71 > 0.5 at 0.125)")
        self.assertEqual(rk4[5], "0.0156 (rotation defect 0.51 > 0.5 at 0.0312)")
        # the cf4 case: 45 % of the energy scale is past the bound, h*(10 s) is below h = 1
        self.assertEqual(rows[("bowl-3d", "rkmk4")][3], "0.5 (energy 0.45 > 0.1 at 1)")
        self.assertEqual(rows[("bowl-3d", "rkmk4")][2], "4 (chart-limit)")
        self.assertEqual(rows[("bumpy-long", "euler")][2], "≤ 0.000977 (domain)")
        self.assertEqual(rows[("bumpy-long", "euler")][3], "none (blow-up at 0.000977: domain)")
        seminar = rows[("bumpy-long", "rkmk4-seminar")]
        self.assertEqual(seminar[2], "1 (chart-limit) at 10 s, 0.5 (chart-limit) at 100 s, 0.5 (chart-limit) at 1000 s")
        self.assertEqual(seminar[3], "0.25 (energy 0.1004 > 0.1 at 0.5)")  # the digits that show it past
        self.assertIn("| scene | integrator | blow-up step (s) | h*(10 s) (s) | h*(100 s) (s) | h*(1000 s) (s) |",
                      text)
        self.assertIn("within 0.1 and ‖RᵀR − I‖_F within 0.5", text)

    def test_the_findings_say_the_blow_up_step_and_h_star_per_horizon(self):
        lines = stability.finding_lines(self.report)
        scene = next(line for line in lines if line.startswith("- Stability on bumpy-long"))
        self.assertIn("rk4: blow-up step 0.5 (defect-blow-up); h*(10 s) 0.0625, h*(100 s) 0.0312, "
                      "h*(1000 s) 0.0156 limited by rotation defect", scene)
        self.assertIn("rkmk4: blow-up step 4 (chart-limit); h*(10 s) 0.5, h*(100 s) 0.25, h*(1000 s) 0.25 "
                      "limited by energy", scene)
        self.assertIn("euler: blow-up step ≤ 0.000977 (domain); h*(10 s) none, h*(100 s) none, h*(1000 s) none "
                      "limited by blow-up", scene)
        self.assertIn("rkmk4-seminar: blow-up step 1 (chart-limit) at 10 s, 0.5 (chart-limit) at 100 s, 0.5 "
                      "(chart-limit) at 1000 s; h*(10 s) 0.25 (energy), h*(100 s) 0.25 (blow-up), h*(1000 s) 0.25 "
                      "(blow-up)", scene)
        self.assertIn("within 10 steps of it", scene)
        self.assertEqual(lines[-1], "- The blow-up step is the same at every horizon (10 s, 100 s, 1000 s) for 6 of "
                         "8 method × scene; it moves for rkmk4-seminar on bumpy-long (1 (chart-limit) at 10 s, 0.5 "
                         "(chart-limit) at 100 s, 0.5 (chart-limit) at 1000 s); rkmk4-seminar on bowl-3d (1 "
                         "(chart-limit) at 10 s, 0.5 (chart-limit) at 100 s, 0.5 (chart-limit) at 1000 s) (a step "
                         "that fails only late, with no drift before: a Newton iteration or the exponential chart "
                         "failing at a state the run reaches only then).")
        self.assertTrue(set(lines) <= set(findings.findings_section(self.report)))

    def test_the_figure_draws_both_limits(self):
        palette = style.Palette(rp.families(self.report))
        fig = figures_overview.stability(self.report, palette)
        labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
        for label in ("h*(10 s)", "h*(1000 s)", "blow-up step", "bumpy-long"):
            self.assertIn(label, labels)
        self.assertIn("drift-limited step", fig.axes[0].get_title())

    def test_the_schema_checks_the_new_keys(self):
        bad = copy.deepcopy(self.report)
        bad["stability"]["largest_stable_h"][0]["drift_limited"][1]["h"] = "0.5"
        with self.assertRaisesRegex(rp.ReportError, r"stability\.largest_stable_h\[0\]\.drift_limited\[1\]\.h is a "
                                                    r"string \('0.5'\)"):
            rp.validate(bad)
        bad = copy.deepcopy(self.report)
        bad["stability"]["largest_stable_h"][0]["blow_up"]["same_at_every_horizon"] = 1
        with self.assertRaisesRegex(rp.ReportError, r"blow_up\.same_at_every_horizon is a number"):
            rp.validate(bad)


class ReportsOfBefore(unittest.TestCase):
    """A report with one largest stable step per entry (no drift_limited) keeps its table and figure."""

    def test_old_entries_keep_the_old_table_and_no_findings_line(self):
        report = syn.make_report()
        self.assertFalse(stability.has_limits(rp.stable_steps(report)))
        text = "\n".join(summary.stability_section(report))
        self.assertIn("largest stable h (s)", text)
        self.assertEqual(stability.finding_lines(report), [])
        fig = figures_overview.stability(report, style.Palette(rp.families(report)))
        self.assertIn("largest stable step", fig.axes[0].get_title())


if __name__ == "__main__":
    unittest.main()

"""Physics stated honestly (issue 56, item 5) on the analysis side: the energy error the figures and findings read
is the one at the nearest rotation where the report has it (the flat one in older reports); a kinematic first
integral is tabulated, marked, and never cited in the findings; the cost axis is in rhs-equivalents, an implicit
method's Jacobians and Newton passes included; the `solver` status has its colour."""
import copy
import math
import unittest

import matplotlib

matplotlib.use("Agg")

from analysis import costs, figures, horizon, style, summary  # noqa: E402
from analysis import markdown as md  # noqa: E402
from analysis import report as rp  # noqa: E402
from tests.analysis import synthetic as syn  # noqa: E402

H = 2.0 ** -7
STEPS = 10000
T = [H * n for n in (1, 3, 10, 32, 100, 316, 1000, 3162, 10000)]


def fit(p, c, cls):
    """A runner's fit of C t^p with its class (the keys of reports with and without growth classes)."""
    return {"p": p, "ci95": 0.01, "log10_c": math.log10(c), "t_from": T[-1] / 100, "t_to": T[-1], "points": 5,
            "largest": c * T[-1] ** p, "rounding_level": 1e-11, "at_rounding": cls == "rounding",
            "p_early": p, "p_late": p, "asymptotic": True, "class": cls, "decades": [], "why_none": None}


def horizon_run(index, name, family, energy, defect, on_group=None):
    """A chaplygin-plane run: energy, defect, on_group: (p, C, class) of C t^p."""
    run = {"index": index, "scene": "chaplygin-plane", "r_feeds_back": True, "integrator": name, "family": family,
           "declared_order": 2, "on_group": family != "rk", "coarsening": 1, "h": H, "steps_planned": STEPS,
           "t_end": T[-1], "status": "ok", "message": "", "stop_time": T[-1], "steps": STEPS,
           "rhs_evals": 4 * STEPS, "exp_evals": 0, "wall_s": 0.25, "cpu_s": 0.25, "energy_scale": 1.2, "t": T,
           "fit": {}}
    laws = {"energy_error": energy, "rotation_defect": defect}
    if on_group:
        laws["energy_error_on_group"] = on_group
    for key, (p, c, cls) in laws.items():
        run[key] = [c * x ** p for x in T]
        run["fit"][key] = fit(p, c, cls)
    return run


def with_dg2(report, new=True):
    """chaplygin-plane: dg2's flat energy at rounding, its energy at the nearest rotation growing like t^1.5;
    rkmk4's two the same; rk4's flat one hides most of its error. Each run records M . M and M . gamma, kinematic,
    which rkmk4 and dg2 keep at rounding, and a made-up dynamical integral that rk4 alone keeps. new=False: the
    report predates both fields."""
    report = dict(report)
    dg2 = horizon_run(0, "dg2", "discrete-gradient", (0.0, 1e-16, "rounding"), (1.0, 1e-9, "linear"),
                      (1.5, 1e-7, "power") if new else None)
    rkmk4 = horizon_run(1, "rkmk4", "rkmk", (0.02, 1e-8, "bounded"), (0.0, 1e-16, "rounding"),
                        (0.02, 1e-8, "bounded") if new else None)
    rk4 = horizon_run(2, "rk4", "rk", (1.0, 1e-12, "linear"), (1.0, 1e-6, "linear"),
                      (1.0, 1e-9, "linear") if new else None)
    laws = {"dg2": ((0.0, 1e-16), (0.0, 1e-16), (1.0, 1e-8)), "rkmk4": ((0.0, 1e-16), (0.0, 1e-16), (1.0, 1e-8)),
            "rk4": ((1.0, 1e-8), (1.0, 1e-8), (0.0, 1e-16))}
    names = (("chaplygin-plane.K.K", "kinematic"), ("chaplygin-plane.K.N", "kinematic"),
             ("made-up.I", "dynamical"))
    for run in (dg2, rkmk4, rk4):
        run["invariants"] = []
        for (name, kind), (p, c) in zip(names, laws[run["integrator"]]):
            entry = {"name": name, "error": [c * x ** p for x in T],
                     "fit": fit(p, c, "rounding" if c < 1e-13 else "linear")}
            if new:
                entry["kind"] = kind
            run["invariants"].append(entry)
    report["horizon"] = {"runs": [dg2, rkmk4, rk4]}
    return report


def section_text(markdown):
    """summary.md's "Long horizons" section."""
    return markdown.split(horizon.HEADING)[1].split("\n## ")[0]


def findings_of(markdown):
    return markdown.split("## Contents")[0]


class EnergyAtTheNearestRotation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = with_dg2(syn.make_report())
        cls.markdown = summary.summary_markdown(cls.report)
        cls.old_report = with_dg2(syn.make_report(), new=False)
        cls.old = summary.summary_markdown(cls.old_report)

    def test_the_runs_read_the_energy_at_the_nearest_rotation(self):
        by = {r["integrator"]: r for r in horizon.runs(self.report, "chaplygin-plane")}
        self.assertEqual(by["dg2"]["energy_error"], [1e-7 * x ** 1.5 for x in T])
        self.assertEqual(horizon.fit_of(by["dg2"], "energy_error")["class"], "power")
        self.assertEqual(by["dg2"]["energy_error_flat"], [1e-16] * len(T))
        # an older report: the flat one, as it was
        old = {r["integrator"]: r for r in horizon.runs(self.old_report, "chaplygin-plane")}
        self.assertEqual(old["dg2"]["energy_error"], [1e-16] * len(T))
        self.assertEqual(horizon.fit_of(old["dg2"], "energy_error")["class"], "rounding")

    def test_the_summary_states_the_energy_at_the_nearest_rotation(self):
        on_group, flat = md.fmt(1e-7 * T[-1] ** 1.5), md.fmt(1e-12 * T[-1])
        self.assertIn(on_group, section_text(self.markdown))
        self.assertNotIn(flat, section_text(self.markdown))  # rk4's flat end value
        self.assertIn(flat, section_text(self.old))
        self.assertIn("nearest rotation", section_text(self.markdown))

    def test_the_findings_no_longer_call_dg2_s_energy_rounding(self):
        line = next(x for x in findings_of(self.markdown).splitlines() if "chaplygin-plane" in x
                    and x.startswith("- Long horizon"))
        old = next(x for x in findings_of(self.old).splitlines() if "chaplygin-plane" in x
                   and x.startswith("- Long horizon"))
        self.assertRegex(old, r"dg2[^;]*rounding|rounding[^;]*dg2")
        self.assertNotRegex(line, r"dg2, rounding|rounding for [^;]*dg2")

    def test_the_figure_draws_the_energy_at_the_nearest_rotation(self):
        palette = style.Palette(rp.families(self.report))
        energy = horizon.figure(self.report, "chaplygin-plane", palette).get_axes()[0]
        dg2 = next(x for x in energy.get_lines() if x.get_label().startswith("dg2"))
        self.assertTrue(all(math.isclose(y, 1e-7 * t ** 1.5, rel_tol=1e-12)
                            for t, y in zip(dg2.get_xdata(), dg2.get_ydata())))
        self.assertIn("polar", energy.get_ylabel())

    def test_the_drift_figure_reads_the_run_s_energy_on_group_and_the_stability_series(self):
        report = copy.deepcopy(syn.make_report())
        scene = "plane"
        for entry in report["runs"]:
            if entry["scene"] == scene:
                entry["drift"]["energy_on_group"] = 7.0 * entry["drift"]["energy"]
                entry["rhs_equivalents"] = 3.0 * entry["rhs_evals"]
        fig = figures.drift(report, scene, style.Palette(rp.families(report)))
        energy = fig.get_axes()[-2]
        rk4 = next(x for x in energy.get_lines() if x.get_label() == "rk4")
        runs = sorted((r for r in rp.runs(report, scene) if r.integrator == "rk4" and rp.ok(r)),
                      key=lambda r: r.rhs_evals)
        self.assertEqual(list(rk4.get_xdata()), [3.0 * r.rhs_evals for r in runs])
        self.assertEqual(list(rk4.get_ydata()), [7.0 * r.entry["drift"]["energy"] for r in runs])
        self.assertIn("rhs-equivalents", energy.get_xlabel())


class KinematicIntegrals(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = with_dg2(syn.make_report())
        cls.markdown = summary.summary_markdown(cls.report)

    def test_the_findings_never_cite_a_kinematic_integral(self):
        findings = self.markdown.split("## Contents")[0]
        self.assertNotIn("chaplygin-plane.K.K", findings)
        self.assertNotIn("chaplygin-plane.K.N", findings)
        # the dynamical one is stated
        line = next(x for x in findings.splitlines() if x.startswith("- Long horizon on chaplygin-plane "))
        self.assertIn("made-up.I", line)

    def test_the_table_lists_and_marks_them(self):
        rows = md.parse_table(self.markdown, horizon.INVARIANT_HEADING)
        self.assertEqual(len(rows), 9)  # three runs, three integrals
        cells = [cell for row in rows for cell in row]
        for name in ("chaplygin-plane.K.K", "chaplygin-plane.K.N"):
            self.assertEqual(cells.count(name + " (kinematic)"), 3)
            self.assertNotIn(name, cells)
        self.assertEqual(cells.count("made-up.I"), 3)
        self.assertIn("no evidence of structure", self.markdown)

    def test_the_figure_marks_their_panels(self):
        axes = horizon.figure(self.report, "chaplygin-plane", style.Palette(rp.families(self.report))).get_axes()
        self.assertEqual(len(axes), 5)
        self.assertIn("kinematic", axes[2].get_title())
        self.assertNotIn("kinematic", axes[4].get_title())

    def test_an_older_report_without_kinds_cites_them_as_before(self):
        old = summary.summary_markdown(with_dg2(syn.make_report(), new=False)).split("## Contents")[0]
        self.assertIn("chaplygin-plane.K.K", old)


class CostInRhsEquivalents(unittest.TestCase):
    def test_the_cost_axis_reads_rhs_equivalents_and_falls_back_to_rhs_evals(self):
        report = copy.deepcopy(syn.make_report())
        scene = "plane"
        before = costs.cost_rows(report, scene)
        for entry in report["runs"]:
            if entry["integrator"] == "rk4":
                entry["rhs_equivalents"] = 10.0 * entry["rhs_evals"]
        after = costs.cost_rows(report, scene)
        for target in costs.TARGETS:
            old, new = before["rk4"][("rhs", target)][0], after["rk4"][("rhs", target)][0]
            self.assertTrue(math.isfinite(old))
            self.assertAlmostEqual(new, 10.0 * old, delta=1e-9 * new)
            # the other methods, and the time axis, unchanged
            self.assertEqual(after["rkmk4"][("rhs", target)], before["rkmk4"][("rhs", target)])
            self.assertEqual(after["rk4"][("time", target)], before["rk4"][("time", target)])
        run = rp.Run.of(next(e for e in report["runs"] if e["integrator"] == "rkmk4"))
        self.assertEqual(costs.rhs_equivalents(run), run.rhs_evals)

    def test_the_tables_name_the_axis(self):
        markdown = summary.summary_markdown(syn.make_report())
        self.assertIn("cheapest by rhs-equivalents", markdown)
        self.assertIn("rhs-equivalents to 1e-06", markdown)


class SolverStatus(unittest.TestCase):
    def test_it_has_a_colour_of_its_own(self):
        self.assertIn("solver", style.STATUS_COLOURS)
        self.assertEqual(len(set(style.STATUS_COLOURS.values())), len(style.STATUS_COLOURS))


if __name__ == "__main__":
    unittest.main()

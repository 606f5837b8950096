"""The horizon study's figure, summary section and findings line from a
hand-made report: power laws with known exponents (the runner's classes
and fits written beside them), a method at rounding level, one that
stopped, one whose class is undecided (its per-decade slopes climbing)
and one whose energy series the report marks the same as another's; a
run the study took on a decade further, one the budget stopped, and a
report older than the classes."""
import math
import os
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

from analysis import horizon, plot, style, summary  # noqa: E402
from analysis import markdown as md  # noqa: E402
from analysis import report as rp  # noqa: E402
from tests.analysis import synthetic as syn  # noqa: E402

H = 2.0 ** -7
STEPS = 10000
T = [H * n for n in (1, 3, 10, 32, 100, 316, 1000, 3162, 10000)]
T_FROM = T[-1] / 1000  # the class window: the last three decades


def band(p):
    """The runner's class of a decided exponent (bench/lib/growth_class.cpp, band_of)."""
    for hi, name in ((0.25, "bounded"), (0.75, "power"), (1.25, "linear"), (1.75, "power"), (2.25, "quadratic")):
        if p <= hi:
            return name
    return "power"


def fit(p, c, at_rounding=False, rounding=1e-11, slopes=None, cls=None):
    """The runner's fit of C t^p: its class (p's band, "rounding" at rounding, or cls) and the slopes over the
    window's three decades (p in each, or slopes)."""
    slopes = slopes or (p, p, p)
    decades = [{"t_from": T[-1] / 10 ** (3 - i), "t_to": T[-1] / 10 ** (2 - i), "p": x, "ci95": 0.02, "points": 9}
               for i, x in enumerate(slopes)]
    cls = cls or ("rounding" if at_rounding else band(p))
    return {"class": cls, "reason": f"{cls} (made by hand)", "p": p, "ci95": 0.01, "log10_c": math.log10(c),
            "t_from": T_FROM, "t_to": T[-1], "points": 25, "largest": c * T[-1] ** p, "rounding_level": rounding,
            "at_rounding": at_rounding, "decades": decades, "p_earlier": sum(slopes[:-1]) / (len(slopes) - 1),
            "ci95_earlier": 0.01, "p_last": slopes[-1], "ci95_last": 0.02}


def no_fit(why):
    return {"class": None, "reason": why, "p": None, "ci95": None, "log10_c": None, "t_from": T_FROM,
            "t_to": T[-1], "points": 0, "largest": None, "rounding_level": 1e-11, "at_rounding": False,
            "decades": [], "p_earlier": None, "ci95_earlier": None, "p_last": None, "ci95_last": None}


def horizon_run(index, scene, name, family, energy, defect, status="ok", stop=None):
    """energy, defect: (p, C) of C t^p, or None for a run that stopped."""
    t = T if stop is None else [x for x in T if x <= stop]
    feeds_back = scene.startswith("chaplygin")
    run = {"index": index, "scene": scene, "r_feeds_back": feeds_back, "integrator": name, "family": family,
           "declared_order": 4, "on_group": family != "rk", "h": H, "steps_planned": STEPS, "t_end": T[-1],
           "status": status, "message": "" if status == "ok" else "left the domain",
           "stop_time": T[-1] if stop is None else stop, "steps": STEPS if stop is None else int(stop / H),
           "rhs_evals": 4 * STEPS, "exp_evals": 0, "wall_s": 0.25, "energy_scale": 1.2, "t": t}
    for key, law in (("energy_error", energy), ("rotation_defect", defect)):
        p, c = law if law else (3.0, 1e-3)  # a stopped run's series still grows; it has no fit
        run[key] = [c * x ** p for x in t]
    if status == "ok":
        run["fit"] = {"energy_error": fit(*energy), "rotation_defect": fit(*defect, at_rounding=defect[1] < 1e-13)}
    else:
        why = f"the run stopped at t = {stop:g} ({status})"
        run["fit"] = {"energy_error": no_fit(why), "rotation_defect": no_fit(why)}
    return run


def with_horizon(report):
    report = dict(report)
    runs = []
    for scene in ("bumpy-long", "chaplygin-bumpy-long"):
        base = len(runs)
        runs += [horizon_run(base, scene, "rk4", "rk", (1.0, 1e-9), (1.0, 1e-6)),
                 horizon_run(base + 1, scene, "rkmk4", "rkmk", (0.5, 1e-10), (0.5, 1e-16)),
                 horizon_run(base + 2, scene, "euler", "rk", None, None, status="domain", stop=12.0)]
        if scene == "bumpy-long":
            moving = horizon_run(base + 3, scene, "cf4", "cf", (0.45, 1e-9), (0.5, 1e-16))
            moving["fit"]["energy_error"] = fit(0.45, 1e-9, slopes=(0.30, 0.45, 0.63), cls="undecided")
            twin = horizon_run(base + 4, scene, "rk4-projected", "projection", (1.0, 1e-9), (0.5, 1e-16))
            twin["same_as"] = {"energy_error": "rk4", "rotation_defect": None}
            runs += [moving, twin]
    report["horizon"] = {"runs": runs}
    return report


def labelled(ax):
    return [line for line in ax.get_lines() if not line.get_label().startswith("_")]


class HorizonFromAHandMadeReport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = with_horizon(syn.make_report())
        cls.markdown = summary.summary_markdown(cls.report)

    def test_figure_has_one_line_per_method_and_the_exponents_in_the_legend(self):
        palette = style.Palette(rp.families(self.report))
        fig = horizon.figure(self.report, "chaplygin-bumpy-long", palette)
        axes = fig.get_axes()
        self.assertEqual(len(axes), 2)
        for ax, key in zip(axes, ("energy_error", "rotation_defect")):
            self.assertEqual(ax.get_xscale(), "log")
            self.assertEqual(ax.get_yscale(), "log")
            labels = [line.get_label() for line in labelled(ax)]
            self.assertEqual(len(labels), 3, labels)
            self.assertIn("euler: domain at t = 12", labels)
        energy = [line.get_label() for line in labelled(axes[0])]
        defect = [line.get_label() for line in labelled(axes[1])]
        self.assertIn("rk4: linear, p = 1.00 ± 0.01", energy)
        self.assertIn("rkmk4: power, p = 0.50 ± 0.01", energy)
        self.assertIn("rkmk4: p = 0.50 ± 0.01 (rounding)", defect)
        # the fitted line is the report's C t^p over its window
        fits = [line for line in axes[1].get_lines() if line.get_label() == "_fit"]
        self.assertEqual(len(fits), 2)  # the stopped run has none
        x, y = fits[0].get_xdata(), fits[0].get_ydata()
        self.assertAlmostEqual(x[0], T_FROM)
        self.assertAlmostEqual(x[-1], T[-1])
        self.assertTrue(np.allclose(y, 1e-6 * x, rtol=1e-12))

    def test_write_all_draws_a_figure_per_horizon_scene(self):
        # the study alone: the sweep's figures (scenes.png runs rollbench) are other tests' business
        report = {"schema": rp.SCHEMA, "runs": [], "references": self.report["references"],
                  "horizon": self.report["horizon"]}
        with tempfile.TemporaryDirectory() as out:
            written = plot.write_all(report, out, plot.Options(scene_dir=os.devnull), log=lambda _: None)
            for scene in ("bumpy-long", "chaplygin-bumpy-long"):
                path = os.path.join(out, f"horizon-{scene}.png")
                self.assertIn(path, written)
                image = mpimg.imread(path)
                self.assertGreater(float(np.std(image[..., :3])), 0.05)  # not blank
            with open(os.path.join(out, "index.html"), encoding="utf-8") as f:
                page = f.read()
            self.assertIn('src="horizon-chaplygin-bumpy-long.png"', page)
            self.assertIn("Long horizons", page)

    def test_summary_section_lists_every_run_with_its_exponents(self):
        rows = md.parse_table(self.markdown, horizon.HEADING)
        self.assertEqual(len(rows), 8)
        by = {(r[0], r[2]): r for r in rows}
        rk4 = by[("chaplygin-bumpy-long", "rk4")]
        self.assertEqual(rk4[1], "R feeds back")
        self.assertEqual(rk4[3], "ok")
        self.assertEqual(rk4[4], "10,000")
        self.assertEqual(rk4[5], "1.00 ± 0.01")
        self.assertEqual(rk4[6], "linear (1.00, 1.00, 1.00)")
        self.assertAlmostEqual(md.as_number(rk4[10]), 1e-6 * T[-1], delta=1e-6 * T[-1] * 1e-2)
        self.assertEqual(by[("bumpy-long", "rkmk4")][1], "homogeneous")
        self.assertEqual(by[("bumpy-long", "rkmk4")][8], "0.50 ± 0.01 (rounding)")
        self.assertEqual(by[("bumpy-long", "rkmk4")][9], "rounding")
        euler = by[("bumpy-long", "euler")]
        self.assertEqual(euler[3], "domain at t = 12")
        self.assertEqual(euler[5], "—")
        self.assertEqual(euler[6], "—")
        self.assertIn(f"- [Long horizons](#{summary.slug('Long horizons')})", self.markdown)
        self.assertIn("over the last 3 decades of t", self.markdown)
        self.assertNotIn("budget ended", self.markdown)  # no run was stopped by the budget
        failures = md.parse_table(self.markdown, "## Failures")
        self.assertIn(["bumpy-long", "euler (horizon run)", "h=0.0078125", "domain", "12", "left the domain"],
                      failures)

    def test_findings_say_who_grows_who_stays_at_rounding_and_who_stopped(self):
        lines = [line for line in self.markdown.splitlines() if line.startswith("- Long horizon on ")]
        self.assertEqual(len(lines), 2)
        line = next(x for x in lines if "chaplygin-bumpy-long" in x)
        self.assertIn("(R feeds back, 10,000 steps of h = 0.0078125 s)", line)
        self.assertIn("energy error ∝ tᵖ with p from 0.50 (rkmk4) to 1.00 (rk4)", line)
        self.assertIn("rotation defect grows for rk4 1.00", line)
        self.assertIn("stays at rounding for rkmk4", line)
        self.assertIn("stopped: euler (domain at t = 12)", line)
        findings = self.markdown.split("## Contents")[0]
        self.assertIn(line, findings)

    def test_an_undecided_class_reads_undecided_with_its_slopes_and_no_p(self):
        rows = {(r[0], r[2]): r for r in md.parse_table(self.markdown, horizon.HEADING)}
        self.assertEqual(rows[("bumpy-long", "cf4")][5], "undecided")
        self.assertEqual(rows[("bumpy-long", "cf4")][6], "undecided (0.30, 0.45, 0.63)")
        self.assertEqual(rows[("bumpy-long", "rk4")][5], "1.00 ± 0.01")
        line = next(x for x in self.markdown.splitlines() if x.startswith("- Long horizon on bumpy-long "))
        self.assertIn("energy error undecided (slopes a decade) for cf4 at 10,000 steps (0.30, 0.45, 0.63)", line)
        self.assertNotIn("(cf4)", line)  # not in the range of exponents
        # the decided classes' exponents
        self.assertIn("energy error ∝ tᵖ with p from 0.50 (rkmk4) to 1.00 (rk4 = rk4-projected)", line)
        palette = style.Palette(rp.families(self.report))
        energy = horizon.figure(self.report, "bumpy-long", palette).get_axes()[0]
        self.assertIn("cf4: undecided at 10,000 steps (0.30, 0.45, 0.63)", [x.get_label() for x in labelled(energy)])
        # no fitted line for it: rk4's (shared with rk4-projected) and rkmk4's only
        self.assertEqual(len([x for x in energy.get_lines() if x.get_label() == "_fit"]), 2)

    def test_a_series_the_same_as_another_is_drawn_and_stated_once(self):
        line = next(x for x in self.markdown.splitlines() if x.startswith("- Long horizon on bumpy-long "))
        # its energy once in the p range and once in the identical-series note; its own defect at rounding
        self.assertEqual(line.count("rk4-projected"), 3)
        self.assertEqual(line.count("rk4 = rk4-projected"), 2)
        self.assertIn("identical energy series (one tableau stepping (v, α)): rk4 = rk4-projected", line)
        rows = {(r[0], r[2]): r for r in md.parse_table(self.markdown, horizon.HEADING)}
        self.assertEqual(rows[("bumpy-long", "rk4-projected")][12], "energy: rk4")
        self.assertEqual(rows[("bumpy-long", "rk4")][12], "—")
        palette = style.Palette(rp.families(self.report))
        energy, defect = horizon.figure(self.report, "bumpy-long", palette).get_axes()
        labels = [line.get_label() for line in labelled(energy)]
        self.assertIn("rk4 = rk4-projected: linear, p = 1.00 ± 0.01", labels)
        self.assertFalse(any(x.startswith("rk4-projected") for x in labels), labels)
        # its defect is its own: drawn
        self.assertIn("rk4-projected: p = 0.50 ± 0.01 (rounding)", [x.get_label() for x in labelled(defect)])

    def test_a_scene_without_invariants_has_no_panel_or_table_for_them(self):
        palette = style.Palette(rp.families(self.report))
        self.assertEqual(len(horizon.figure(self.report, "bumpy-long", palette).get_axes()), 3 - 1)
        self.assertNotIn(horizon.INVARIANT_HEADING, self.markdown)

    def test_a_report_without_the_study(self):
        report = syn.make_report()
        self.assertEqual(horizon.runs(report), [])
        self.assertIn("no horizon study", "\n".join(horizon.section(report)))
        self.assertEqual(horizon.finding_lines(report), [])
        self.assertEqual(horizon.scenes(report), [])  # plot.py draws horizon-<scene>.png for these only


def with_decades(report):
    """gaussian-hills-chaplygin: rk4 linear at the study's 10,000 steps; gauss2 undecided at 10,000 and at
    100,000 steps, where the budget ended it; dla2 undecided at 10,000 steps, then bounded at 100,000."""
    report = dict(report)
    scene = "gaussian-hills-chaplygin"
    rk4 = horizon_run(0, scene, "rk4", "rk", (1.0, 1e-9), (1.0, 1e-6))
    gauss = horizon_run(1, scene, "gauss2", "gauss", (0.6, 1e-9), (0.5, 1e-16))
    dla = horizon_run(2, scene, "dla2", "nonholonomic-variational", (0.01, 1e-8), (0.5, 1e-16))
    gauss["fit"]["energy_error"] = fit(0.6, 1e-9, slopes=(0.58, 0.78, -0.13), cls="undecided")
    for run in (rk4, gauss, dla):
        run["r_feeds_back"] = True
        run["study_steps"] = STEPS
        run["earlier_runs"] = []
    for run in (gauss, dla):
        run["steps_planned"] = 10 * STEPS
        run["earlier_runs"] = [{"steps": STEPS, "t_end": T[-1], "status": "ok", "cpu_s": 1.0, "wall_s": 1.5,
                                "largest": {"energy_error": 1e-6, "energy_error_on_group": 1e-6,
                                            "rotation_defect": 1e-15},
                                "class": {"energy_error": "undecided", "energy_error_on_group": "undecided",
                                          "rotation_defect": "rounding"}}]
    gauss["budget_ran_out"] = True
    gauss["budget_reason"] = "the next decade, 1000000 steps, is past the study's most, 100000 (--horizon-steps-max)"
    report["horizon"] = {"runs": [rk4, gauss, dla]}
    return report


class HorizonDecades(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = with_decades(syn.make_report())
        cls.markdown = summary.summary_markdown(cls.report)

    def line(self):
        return next(x for x in self.markdown.splitlines() if x.startswith("- Long horizon on gaussian-hills-ch"))

    def test_the_findings_say_where_the_budget_ended_an_undecided_class(self):
        line = self.line()
        self.assertIn("(R feeds back, 10,000 steps (undecided runs on to 100,000) of h = 0.0078125 s)", line)
        self.assertIn("energy error undecided (slopes a decade) for gauss2 at 100,000 steps (0.58, 0.78, -0.13)",
                      line)
        self.assertIn("the budget ended the study undecided for gauss2", line)
        # the decided classes only in the range of exponents
        self.assertIn("energy error ∝ tᵖ with p from 0.01 (dla2) to 1.00 (rk4)", line)
        self.assertIn("Undecided where the budget ended the study (the next decade not run):", self.markdown)
        self.assertIn("- gauss2 on gaussian-hills-chaplygin at 100,000 steps: the next decade, 1000000 steps, is "
                      "past the study's most, 100000 (--horizon-steps-max)", self.markdown)
        self.assertIn("3 runs, 2 of them run again a decade on", self.markdown)

    def test_the_figure_draws_the_longest_run_and_its_title_says_so(self):
        palette = style.Palette(rp.families(self.report))
        energy = horizon.figure(self.report, "gaussian-hills-chaplygin", palette).get_axes()[0]
        self.assertIn("10,000 steps (undecided runs on to 100,000)", energy.get_title())
        labels = [x.get_label() for x in labelled(energy)]
        self.assertIn("gauss2: undecided at 100,000 steps (0.58, 0.78, -0.13)", labels)
        self.assertIn("dla2: bounded, p = 0.01 ± 0.01", labels)

    def test_a_report_older_than_the_classes_decides_nothing(self):
        report = with_horizon(syn.make_report())
        for run in report["horizon"]["runs"]:
            for f in run["fit"].values():
                f.pop("class")
                f.pop("decades")
        markdown = summary.summary_markdown(report)
        line = next(x for x in markdown.splitlines() if x.startswith("- Long horizon on chaplygin-bumpy-long "))
        self.assertNotIn("∝ tᵖ", line)
        self.assertIn("energy error undecided (slopes a decade) for rk4 at 10,000 steps", line)
        self.assertIn("stays at rounding for rkmk4", line)


def with_invariants(report):
    """A paraboloid whose runs record Routh's two integrals: rk4's grow like t and t^2, rkmk4's stay at
    rounding, euler stopped, cf4's are rk4's (the report's same_as)."""
    report = dict(report)
    runs = [horizon_run(0, "paraboloid", "rk4", "rk", (1.0, 1e-9), (1.0, 1e-6)),
            horizon_run(1, "paraboloid", "rkmk4", "rkmk", (0.5, 1e-10), (0.5, 1e-16)),
            horizon_run(2, "paraboloid", "euler", "rk", None, None, status="domain", stop=12.0)]
    twin = horizon_run(3, "paraboloid", "cf4", "cf", (1.0, 1e-9), (0.5, 1e-16))
    twin["same_as"] = {"energy_error": "rk4", "rotation_defect": None,
                       "invariants": {"routh-paraboloid.J1": "rk4", "routh-paraboloid.J2": "rk4"}}
    runs.append(twin)
    laws = {"rk4": ((1.0, 1e-8), (2.0, 1e-12)), "rkmk4": ((0.5, 1e-16), (0.5, 1e-16)), "euler": (None, None),
            "cf4": ((1.0, 1e-8), (2.0, 1e-12))}
    for run in runs:
        run["invariants"] = []
        for name, law in zip(("routh-paraboloid.J1", "routh-paraboloid.J2"), laws[run["integrator"]]):
            p, c = law or (3.0, 1e-3)
            entry = {"name": name, "error": [c * x ** p for x in run["t"]]}
            entry["fit"] = fit(p, c, at_rounding=c < 1e-13) if law else no_fit("the run stopped at t = 12 (domain)")
            run["invariants"].append(entry)
    report["horizon"] = {"runs": runs}
    return report


class HorizonInvariants(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = with_invariants(syn.make_report())
        cls.markdown = summary.summary_markdown(cls.report)

    def test_each_integral_gets_a_panel_with_its_exponents(self):
        palette = style.Palette(rp.families(self.report))
        axes = horizon.figure(self.report, "paraboloid", palette).get_axes()
        self.assertEqual(len(axes), 4)
        self.assertIn("routh-paraboloid.J1 error", axes[2].get_title())
        self.assertIn("routh-paraboloid.J2 error", axes[3].get_title())
        j1 = [line.get_label() for line in labelled(axes[2])]
        j2 = [line.get_label() for line in labelled(axes[3])]
        self.assertIn("rk4 = cf4: linear, p = 1.00 ± 0.01", j1)
        self.assertIn("rk4 = cf4: quadratic, p = 2.00 ± 0.01", j2)
        self.assertFalse(any(x.startswith("cf4") for x in j1 + j2), j1 + j2)  # drawn once, under rk4
        self.assertIn("rkmk4: p = 0.50 ± 0.01 (rounding)", j2)
        self.assertIn("euler: domain at t = 12", j1)
        fits = [line for line in axes[3].get_lines() if line.get_label() == "_fit"]
        self.assertTrue(np.allclose(fits[0].get_ydata(), 1e-12 * fits[0].get_xdata() ** 2, rtol=1e-12))

    def test_the_summary_tables_each_integral_of_each_run(self):
        rows = md.parse_table(self.markdown, horizon.INVARIANT_HEADING)
        self.assertEqual(len(rows), 8)
        by = {(r[1], r[2]): r for r in rows}
        self.assertEqual(by[("rk4", "routh-paraboloid.J2")][3], "2.00 ± 0.01")
        self.assertEqual(by[("rk4", "routh-paraboloid.J2")][4], "quadratic (2.00, 2.00, 2.00)")
        end = 1e-8 * T[-1]
        self.assertAlmostEqual(md.as_number(by[("rk4", "routh-paraboloid.J1")][5]), end, delta=end * 1e-2)
        self.assertEqual(by[("rkmk4", "routh-paraboloid.J1")][3], "0.50 ± 0.01 (rounding)")
        self.assertEqual(by[("euler", "routh-paraboloid.J1")][3], "—")
        self.assertEqual(by[("cf4", "routh-paraboloid.J2")][6], "rk4")
        self.assertEqual(by[("rk4", "routh-paraboloid.J2")][6], "—")
        # the main table is still one row a run
        self.assertEqual(len(md.parse_table(self.markdown, horizon.HEADING)), 4)

    def test_findings_state_each_integral(self):
        line = next(x for x in self.markdown.splitlines() if x.startswith("- Long horizon on paraboloid "))
        self.assertIn("routh-paraboloid.J1 error ∝ tᵖ with p = 1.00 (rk4 = cf4)", line)
        self.assertIn("routh-paraboloid.J2 error ∝ tᵖ with p = 2.00 (rk4 = cf4)", line)
        self.assertIn("routh-paraboloid.J1 at rounding for rkmk4", line)


if __name__ == "__main__":
    unittest.main()

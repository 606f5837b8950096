"""What keeps the energy bounded and at what price (analysis/horizon_ladder.py), on a hand-made report: a
symmetric method (its sweep's reversibility defects at rounding) whose energy stays bounded on one scene and grows
on another, an explicit one whose energy grows, their CPU times, and the cost figure."""
import os
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

from analysis import horizon_ladder as ladder  # noqa: E402
from analysis import plot  # noqa: E402
from tests.analysis import synthetic as syn  # noqa: E402
from tests.analysis.test_horizon import fit, horizon_run  # noqa: E402


def sweep_run(scene, name, defect):
    """A fixed-step sweep run with a measured reversibility defect."""
    return {"scene": scene, "integrator": name, "adaptive": False, "h": 0.01, "status": "ok",
            "reversibility": {"status": "ok", "worst": defect}}


def ladder_report():
    report = dict(syn.make_report())
    report["runs"] = list(report["runs"]) + [sweep_run("paraboloid", "gauss2", 3e-15),
                                             sweep_run("paraboloid", "rk4", 2e-8)]
    runs = []
    # gauss2: bounded and small on the paraboloid; growing to 2e-6 of the 1.2 J scale on the hills
    for scene, gauss_law in (("paraboloid", (0.02, 1e-9)), ("gaussian-hills", (0.70, 1e-7))):
        base = len(runs)
        gauss = horizon_run(base, scene, "gauss2", "gauss", gauss_law, (0.5, 1e-16))
        rk4 = horizon_run(base + 1, scene, "rk4", "rk", (1.0, 1e-7), (1.0, 1e-6))
        euler = horizon_run(base + 2, scene, "euler", "rk", None, None, status="domain", stop=12.0)
        gauss["cpu_s"], rk4["cpu_s"], euler["cpu_s"] = 2.5, 0.25, 0.01
        runs += [gauss, rk4, euler]
    report["horizon"] = {"runs": runs}
    return report


class Ladder(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = ladder_report()
        cls.lines = ladder.finding_lines(cls.report)

    def test_symmetry_is_read_from_the_measured_defects(self):
        self.assertEqual(ladder.symmetric_methods(self.report), {"gauss2"})

    def test_each_scene_says_which_symmetric_method_keeps_the_energy_and_the_price(self):
        para = next(line for line in self.lines if line.startswith("- Ladder, paraboloid "))
        self.assertIn("energy bounded for the symmetric gauss2 (p = 0.02)", para)
        self.assertIn("growing for 1 other method (p = 1.00)", para)
        # rk4's largest error 1e-7 t over t = 78 s is 6.5e-6 of the 1.2 J scale: over 1e-6; gauss2's is not
        self.assertIn("cheapest under 1e-06 relative energy error: gauss2, 2.5 s CPU (10.0 × rk4's 0.25 s at h)",
                      para)
        hills = next(line for line in self.lines if line.startswith("- Ladder, gaussian-hills "))
        self.assertIn("growing for the symmetric gauss2 (p = 0.70)", hills)
        self.assertIn("no run keeps the relative energy error under 1e-06 (steps h)", hills)

    def test_a_price_run_at_a_coarser_step_is_priced_but_not_fitted(self):
        report = dict(self.report)
        runs = list(report["horizon"]["runs"])
        # gauss2 at 4 h stays under the target for a quarter of the price; rk4 at 4 h grows faster and is no
        # second "other method"
        gauss4h = dict(next(r for r in runs if r["integrator"] == "gauss2"), index=len(runs), coarsening=4,
                       cpu_s=0.7)
        gauss4h["energy_error"] = [16 * e for e in gauss4h["energy_error"]]
        rk4_4h = dict(next(r for r in runs if r["integrator"] == "rk4"), index=len(runs) + 1, coarsening=4,
                      cpu_s=0.07)
        report["horizon"] = {"runs": runs + [gauss4h, rk4_4h]}
        para = next(line for line in ladder.finding_lines(report) if line.startswith("- Ladder, paraboloid "))
        self.assertIn("cheapest under 1e-06 relative energy error: gauss2 at 4 h, 0.7 s CPU (2.8 × rk4's 0.25 s at h)",
                      para)
        self.assertIn("growing for 1 other method (p = 1.00)", para)
        # over the target at 4 h (a hundred times more error): the study's own run is the price again
        gauss4h["energy_error"] = [100 * e for e in gauss4h["energy_error"]]
        para = next(line for line in ladder.finding_lines(report) if line.startswith("- Ladder, paraboloid "))
        self.assertIn("gauss2, 2.5 s CPU", para)
        hills = next(line for line in ladder.finding_lines(report) if line.startswith("- Ladder, gaussian-hills "))
        self.assertIn("no run keeps the relative energy error under 1e-06 (steps h)", hills)

    def test_the_last_line_names_where_symmetry_kept_the_energy_and_where_not(self):
        self.assertEqual(self.lines[-1], "- Reversibility and the energy (decided classes only; bounded: p ≤ 0.25 or "
                                         "rounding): symmetry kept every symmetric method's energy bounded on "
                                         "paraboloid; a symmetric method's energy grew on gaussian-hills.")

    def test_classes_of_a_growth_fit(self):
        runs = self.report["horizon"]["runs"]
        self.assertEqual([ladder.energy_class(r) for r in runs[:3]], ["bounded", "grows", None])
        self.assertEqual(ladder.relative_energy_error(runs[2]), float("inf"))

    def test_without_a_measured_symmetric_method_it_says_so(self):
        report = dict(self.report, runs=[r for r in self.report["runs"] if "reversibility" not in r])
        self.assertEqual(len(ladder.finding_lines(report)), 1)
        self.assertIn("no method's reversibility defect was at rounding", ladder.finding_lines(report)[0])

    def test_the_cost_figure_is_drawn(self):
        report = {"schema": self.report["schema"], "runs": [], "references": self.report["references"],
                  "horizon": self.report["horizon"]}
        with tempfile.TemporaryDirectory() as out:
            written = plot.write_all(report, out, plot.Options(scene_dir=os.devnull), log=lambda _: None)
            path = os.path.join(out, ladder.COST_FIGURE)
            self.assertIn(path, written)
            self.assertGreater(float(np.std(mpimg.imread(path)[..., :3])), 0.05)


def variational_report():
    """gauss2 (symmetric) and dla2 (variational, symmetric) on a paraboloid where both stay bounded, dla2's error
    ten times gauss2's, and on hills where gauss2's grows and dla2's stays bounded; dg2 at rounding beside them."""
    report = dict(syn.make_report())
    report["runs"] = list(report["runs"]) + [sweep_run(s, n, 3e-15) for s in ("paraboloid", "gaussian-hills")
                                             for n in ("gauss2", "dla2", "dg2")]
    runs = []
    for scene, gauss_law in (("paraboloid", (0.02, 1e-9)), ("gaussian-hills", (0.70, 1e-7)),
                             ("gaussian-hills-chaplygin", (0.30, 1e-7))):
        base = len(runs)
        gauss = horizon_run(base, scene, "gauss2", "gauss", gauss_law, (0.5, 1e-16))
        dla = horizon_run(base + 1, scene, "dla2", ladder.VARIATIONAL_FAMILY, (0.01, 1e-8), (0.5, 1e-16))
        dg = horizon_run(base + 2, scene, "dg2", ladder.DISCRETE_GRADIENT_FAMILY, (0.5, 1e-16), (0.5, 1e-16))
        gauss["fit"]["energy_error"]["p"], dla["fit"]["energy_error"]["p"] = gauss_law[0], 0.01
        dg["fit"]["energy_error"].update(at_rounding=True, **{"class": "rounding"})
        if scene == "gaussian-hills-chaplygin":  # gauss2's slopes still climb: undecided
            gauss["fit"]["energy_error"] = fit(0.30, 1e-7, slopes=(0.17, 0.59, 0.77), cls="undecided")
        gauss["cpu_s"], dla["cpu_s"], dg["cpu_s"] = 2.0, 1.0, 3.0
        runs += [gauss, dla, dg]
    report["horizon"] = {"runs": runs}
    return report


class Variational(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.report = variational_report()
        cls.lines = ladder.finding_lines(cls.report)

    def test_each_scene_compares_the_variational_method_with_symmetry_alone(self):
        para = next(line for line in self.lines if line.startswith("- Variational structure, paraboloid:"))
        self.assertIn("symmetric, not variational: gauss2 (p = 0.02, ", para)
        self.assertIn("discrete gradient: dg2 (rounding, ", para)
        # both bounded: nothing added, dla2's largest error (1e-8 t^0.01) ten times gauss2's (1e-9 t^0.02) or so
        self.assertIn("symmetry alone kept it bounded too (gauss2): no boundedness added, its largest error", para)
        self.assertIn("CPU dla2 1 s, gauss2 2 s, dg2 3 s.", para)
        hills = next(line for line in self.lines if line.startswith("- Variational structure, gaussian-hills:"))
        self.assertIn("it keeps the energy bounded where symmetry alone did not (gauss2)", hills)
        chaplygin = next(line for line in self.lines if line.startswith("- Variational structure, gaussian-hills-ch"))
        self.assertIn("it keeps the energy bounded where symmetry alone is still undecided (gauss2)", chaplygin)

    def test_the_last_line_sums_it_up_over_the_scenes(self):
        self.assertEqual(self.lines[-1], "- What the variational structure adds to the energy (a discrete "
                                         "Lagrange–d'Alembert method beside the symmetric, non-variational ones): "
                                         "bounded where symmetry alone was not on gaussian-hills; bounded where "
                                         "symmetry alone is still undecided on gaussian-hills-chaplygin; nothing "
                                         "beyond symmetry on paraboloid.")

    def test_one_bounded_symmetric_method_is_enough_for_symmetry_alone(self):
        # beside a grown and an undecided symmetric method, one that stays bounded: nothing added on that scene
        report = variational_report()
        runs = report["horizon"]["runs"]
        for scene in ("gaussian-hills", "gaussian-hills-chaplygin"):
            held = dict(next(r for r in runs if r["scene"] == "paraboloid" and r["integrator"] == "gauss2"),
                        scene=scene, integrator="lie-gauss2", family="lie-gauss", index=len(runs))
            runs.append(held)
        report["runs"] = list(report["runs"]) + [sweep_run(s, "lie-gauss2", 3e-15)
                                                 for s in ("gaussian-hills", "gaussian-hills-chaplygin")]
        lines = ladder.finding_lines(report)
        for scene in ("gaussian-hills", "gaussian-hills-chaplygin"):
            line = next(x for x in lines if x.startswith(f"- Variational structure, {scene}:"))
            self.assertIn("symmetry alone kept it bounded too (lie-gauss2): no boundedness added", line)
        self.assertIn("nothing beyond symmetry on paraboloid, gaussian-hills, gaussian-hills-chaplygin", lines[-1])

    def test_only_decided_classes_are_compared(self):
        # gaussian-hills: gauss2 grows, dla2 bounded ("bounded where symmetry alone did not"); add a symmetric
        # lie-gauss2 that is undecided there, and the claim waits for it
        report = variational_report()
        runs = report["horizon"]["runs"]
        undecided = dict(next(r for r in runs if r["scene"] == "gaussian-hills" and r["integrator"] == "gauss2"),
                         integrator="lie-gauss2", family="lie-gauss", index=len(runs))
        undecided["fit"] = dict(undecided["fit"], energy_error=fit(0.3, 1e-7, slopes=(0.1, 0.3, 0.5),
                                                                   cls="undecided"))
        runs.append(undecided)
        report["runs"] = list(report["runs"]) + [sweep_run("gaussian-hills", "lie-gauss2", 3e-15)]
        line = next(x for x in ladder.finding_lines(report) if x.startswith("- Variational structure, gaussian-hills:"))
        self.assertNotIn("where symmetry alone did not", line)
        self.assertIn("it keeps the energy bounded where symmetry alone is still undecided (lie-gauss2; gauss2 grow)",
                      line)
        # the variational method undecided: nothing compared, whatever the others do
        dla = next(r for r in runs if r["scene"] == "gaussian-hills" and r["integrator"] == "dla2")
        dla["fit"] = dict(dla["fit"], energy_error=fit(0.1, 1e-8, slopes=(0.02, 0.02, 0.20), cls="undecided"))
        lines = ladder.finding_lines(report)
        line = next(x for x in lines if x.startswith("- Variational structure, gaussian-hills:"))
        self.assertIn("dla2's energy undecided at 10,000 steps (0.02, 0.02, 0.20)", line)
        self.assertIn("not compared: its class is undecided", line)
        self.assertNotIn("bounded where", line)
        self.assertIn("undecided on gaussian-hills", lines[-1])
        self.assertNotIn("bounded where symmetry alone was not on gaussian-hills", lines[-1])

    def test_a_run_taken_a_decade_further_is_priced_over_the_study_s_horizon(self):
        # gauss2 on the paraboloid went on to 10 times the steps (12.5 s CPU); its first run, over the study's
        # horizon, took 1.2 s and reached 5e-7 of the energy scale
        report = ladder_report()
        gauss = next(r for r in report["horizon"]["runs"]
                     if r["scene"] == "paraboloid" and r["integrator"] == "gauss2")
        gauss["cpu_s"] = 12.5
        gauss["earlier_runs"] = [{"steps": 10000, "t_end": 78.125, "status": "ok", "cpu_s": 1.2, "wall_s": 1.3,
                                  "largest": {"energy_error": 6e-7, "energy_error_on_group": None,
                                              "rotation_defect": 1e-16},
                                  "class": {"energy_error": "undecided", "energy_error_on_group": None,
                                            "rotation_defect": "rounding"}}]
        self.assertAlmostEqual(ladder.relative_energy_error(gauss), 6e-7 / 1.2)
        self.assertEqual(ladder.cpu_seconds(gauss), 1.2)
        para = next(x for x in ladder.finding_lines(report) if x.startswith("- Ladder, paraboloid "))
        self.assertIn("cheapest under 1e-06 relative energy error: gauss2, 1.2 s CPU (4.8 × rk4's 0.25 s at h)", para)

    def test_no_variational_run_no_line(self):
        self.assertFalse([line for line in ladder.finding_lines(ladder_report()) if "ariational" in line])


if __name__ == "__main__":
    unittest.main()

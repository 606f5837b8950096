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
from tests.analysis.test_horizon import horizon_run  # noqa: E402


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
        self.assertEqual(self.lines[-1], "- Reversibility and the energy (bounded: p ≤ 0.25 or rounding): symmetry "
                                         "kept every symmetric method's energy bounded on paraboloid; a symmetric "
                                         "method's energy grew on gaussian-hills.")

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
        dg["fit"]["energy_error"]["at_rounding"] = True
        if scene == "gaussian-hills-chaplygin":  # gauss2's halves disagree: undecided
            gauss["fit"]["energy_error"].update(p_early=0.01, p_late=0.5, asymptotic=False)
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

    def test_no_variational_run_no_line(self):
        self.assertFalse([line for line in ladder.finding_lines(ladder_report()) if "ariational" in line])


if __name__ == "__main__":
    unittest.main()

"""The findings' reversibility line from a synthetic report whose fixed-step runs carry planted defects: one
method at rounding at every step, the others missing by C h^5, a leg back that stopped and adaptive runs left
out; the line must name exactly those and each one's largest defect with its step."""
import unittest

from analysis import findings, reversibility
from tests.analysis import synthetic as syn

# planted: (C, p) with defect C h^p; gsl-rk4 plays a symmetric method at rounding
PLANTED = {"rk4": (5.0, 5), "rkmk4": (0.5, 5), "gsl-rk4": (3e-15, 0)}


def planted_report():
    report = syn.make_report()
    for r in report["runs"]:
        if r["adaptive"] or r["status"] != "ok":
            r["reversibility"] = None
            continue
        c, p = PLANTED.get(r["integrator"], (None, None))
        if c is None:
            r["reversibility"] = None
        elif r["integrator"] == "rkmk4" and r["scene"] == "plane" and r["h"] == syn.HS[0]:
            r["reversibility"] = {"status": "diverged", "message": "back: the state is not finite"}
        else:
            worst = c * r["h"] ** p
            r["reversibility"] = {"status": "ok", "contact": worst / 2, "rotation": worst, "momentum": worst / 3,
                                  "worst": worst}
    return report


class ReversibilityFindings(unittest.TestCase):
    def test_largest_defect_per_method_with_its_step(self):
        largest = reversibility.largest_defects(planted_report(), "plane")
        self.assertEqual(set(largest), {"rk4", "rkmk4", "gsl-rk4"})
        self.assertEqual(largest["rk4"], (5.0 * syn.HS[0] ** 5, syn.HS[0]))
        # the run whose leg back stopped has no distance: the next step's is the largest
        self.assertEqual(largest["rkmk4"], (0.5 * syn.HS[1] ** 5, syn.HS[1]))
        self.assertEqual(largest["gsl-rk4"][0], 3e-15)

    def test_findings_name_the_methods_at_rounding_and_the_misses(self):
        section = "\n".join(findings.findings_section(planted_report()))
        self.assertIn("- Reversibility on plane (v → −v, run back, v → −v; the largest defect over each fixed-step "
                      "method's runs): back at the start to rounding (≤ 1e-10) at every step for gsl-rk4; missed by "
                      f"rk4 {5.0 * syn.HS[0] ** 5:.3g} (h = 0.0625), rkmk4 {0.5 * syn.HS[1] ** 5:.3g} "
                      "(h = 0.0312).", section)
        self.assertIn("- Reversibility on valley-sideways", section)

    def test_a_report_without_defects_has_no_line(self):
        self.assertEqual(reversibility.finding_lines(syn.make_report()), [])


if __name__ == "__main__":
    unittest.main()

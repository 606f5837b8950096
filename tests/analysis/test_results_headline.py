"""The README's headline (analysis/results.py): one line per scene where R
feeds back and the scenes where the flat method wins named, both ways."""
import copy
import unittest

from analysis import findings, results
from tests.analysis import synthetic as syn


def slowed(report, on_group, factor):
    """A copy with every run on one side (Lie or flat) factor times slower, in every timed sample."""
    out = copy.deepcopy(report)
    for r in out["runs"]:
        if bool(r.get("on_group")) == on_group:
            w = r["wall_s"]
            for key in ("median", "min", "max"):
                w[key] *= factor
            w["samples"] = [s * factor for s in w["samples"]]
    return out


class Headline(unittest.TestCase):
    def block(self, report):
        return "\n".join(results.readme_block(report, "page.md"))

    def test_names_the_scene_where_the_flat_method_wins(self):
        text = self.block(slowed(syn.make_report(), True, 100.0))
        self.assertIn("- The flat method wins on: valley-sideways.", text)
        self.assertRegex(text, r"  - valley-sideways: \*\*the flat method wins\*\* in (\d+) of \1 pair")

    def test_names_none_when_the_lie_method_wins(self):
        text = self.block(slowed(syn.make_report(), False, 100.0))
        self.assertIn("- The flat method wins on: no scene where R feeds back.", text)
        self.assertIn("  - valley-sideways: the Lie method is cheaper in ", text)
        self.assertNotIn("  - plane:", text)  # homogeneous: not a scene where R feeds back


class Answer(unittest.TestCase):
    """The findings open with the answer, before any definition, both ways."""

    def opening(self, report):
        return findings.findings_section(report)[2]

    def test_lie_loses(self):
        text = self.opening(slowed(syn.make_report(), True, 100.0))
        self.assertTrue(text.startswith("**Where R feeds back, keeping R on SO(3) pays on 0 of 1 scenes**"), text)
        self.assertIn("The flat method wins on valley-sideways (", text)

    def test_lie_wins(self):
        text = self.opening(slowed(syn.make_report(), False, 100.0))
        self.assertTrue(text.startswith("**Where R feeds back, keeping R on SO(3) pays on 1 of 1 scenes**"), text)
        self.assertIn(" The flat method wins on none. ", text)


if __name__ == "__main__":
    unittest.main()

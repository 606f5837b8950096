"""The first screen answers: summary.md and index.html open with the answer
sentences (their numbers computed here from the synthetic model), then
answer.png, then the definitions; every figure has a caption that is not
its file name; convergence legends give an order only with its interval
and verdict; the every-method charts live on all-methods.html."""
import copy
import math
import os
import re
import tempfile
import unittest

from analysis import answer, captions, costs, figures, html, plot, style, summary
from tests.analysis import synthetic as syn
from tests.analysis.test_summary import model_cost

SCENE = "valley-sideways"  # the synthetic report's one scene where R feeds back
# (flat, Lie) of each Lie method with a tableau on it: one flat partner each in the synthetic report
LIE_PAIRS = [("rk4", "rkmk4"), ("odeint-fehlberg78", "rkmk8"),
             ("odeint-fehlberg78-adaptive", "rkmk-f78-adaptive"), ("odeint-dopri5-adaptive", "rkmk-dp54-adaptive")]
DEFINITIONS = "Which method is cheapest at"  # the findings' definitions paragraph begins so


def model_median(scene, lie_factor=1.0):
    """The answer's number from the model: the median (upper of an even count) flat/Lie cell, bounds left out.

    The findings read error_max, ERROR_MAX_FACTOR times the error at t_end,
    so a target t there is t / ERROR_MAX_FACTOR of the model's error.
    """
    ratios = []
    for flat, lie in LIE_PAIRS:
        for target in costs.TARGETS:
            a, bound_a = model_cost(scene, flat, "time", target / syn.ERROR_MAX_FACTOR)
            b, bound_b = model_cost(scene, lie, "time", target / syn.ERROR_MAX_FACTOR)
            if math.isfinite(a) and math.isfinite(b) and not bound_a and not bound_b:
                ratios.append(a / (b * lie_factor))
    ratios.sort()
    return ratios[len(ratios) // 2]


def slowed_lie(report, factors):
    """A copy with every Lie run's timed repeat k multiplied by factors[k]."""
    out = copy.deepcopy(report)
    for r in out["runs"]:
        if r.get("on_group"):
            r["wall_s"]["samples"] = [s * f for s, f in zip(r["wall_s"]["samples"], factors)]
    return out


def opening(markdown):
    """summary.md's first paragraph that is no heading."""
    return next(line for line in markdown.splitlines() if line.strip() and not line.startswith("#"))


def scene_numbers(text, scene):
    found = re.search(re.escape(scene) + r" \((\d+\.\d\d) \[(\d+\.\d\d)–(\d+\.\d\d)\]", text)
    if not found:
        raise AssertionError(f"no '{scene} (median [low–high])' in: {text}")
    return tuple(float(x) for x in found.groups())


class AnswerSentences(unittest.TestCase):
    def test_the_summary_opens_with_the_answer_and_its_numbers(self):
        text = opening(summary.summary_markdown(syn.make_report()))
        self.assertTrue(text.startswith("**Where R feeds back, keeping R on SO(3) pays on 0 of 1 scenes**"), text)
        median, low, high = scene_numbers(text.split("The flat method wins on ")[1], SCENE)
        expected = model_median(SCENE)
        # equal timing noise on both sides: every repeat gives the same ratio
        for value in (median, low, high):
            self.assertAlmostEqual(value, expected, delta=0.006)
        self.assertEqual(len(re.findall(r"[.!?](?:\s|$)", text)), 3, text)  # three sentences

    def test_the_interval_is_the_repeats_lowest_to_highest(self):
        # repeat 1 of every Lie run twice as slow: that repeat's ratio halves, the median stays
        text = opening(summary.summary_markdown(slowed_lie(syn.make_report(), (1, 2, 1, 1, 1))))
        median, low, high = scene_numbers(text, SCENE)
        expected = model_median(SCENE)
        self.assertAlmostEqual(median, expected, delta=0.006)
        self.assertAlmostEqual(low, expected / 2, delta=0.006)
        self.assertAlmostEqual(high, expected, delta=0.006)

    def test_a_scene_where_the_lie_method_pays_is_named_with_its_ratio(self):
        text = opening(summary.summary_markdown(slowed_lie(syn.make_report(), [0.5] * 5)))
        self.assertTrue(text.startswith("**Where R feeds back, keeping R on SO(3) pays on 1 of 1 scenes**: "), text)
        self.assertIn("The flat method wins on none.", text)
        median, _, _ = scene_numbers(text, SCENE)
        self.assertAlmostEqual(median, model_median(SCENE, 0.5), delta=0.006)

    def test_repeats_on_both_sides_of_one_are_said(self):
        # the Lie side 20 % faster in one repeat and 40 % slower in another: the ratio's repeats straddle 1
        factor = model_median(SCENE)  # the Lie side slowed to ratio 1 in the plain repeats
        text = opening(summary.summary_markdown(slowed_lie(syn.make_report(),
                                                           [factor * f for f in (1, 0.8, 1, 1.4, 1)])))
        self.assertIn(f"{SCENE} (", text)
        self.assertIn("the repeats straddle 1)", text)

    def test_no_scene_where_r_feeds_back_says_so_and_draws_no_figure(self):
        report = copy.deepcopy(syn.make_report())
        for ref in report["references"]:
            ref["r_feeds_back"] = False
        markdown = summary.summary_markdown(report)
        self.assertTrue(opening(markdown).startswith("**No scene where R feeds back has a measured flat/Lie ratio"))
        self.assertNotIn(answer.FIGURE, markdown)
        messages = []
        self.assertNotIn(answer.FIGURE, plot.build_figures(report, plot.Options(scene_figures=False), messages))
        self.assertTrue(any(m.startswith(f"skipped {answer.FIGURE}: ") for m in messages), messages)


def written_pages(report):
    """(index.html, all-methods.html, file names) of plot.write_all on report, in a folder removed after."""
    with tempfile.TemporaryDirectory() as out:
        plot.write_all(report, out, plot.Options(scene_dir=os.devnull), log=lambda _: None)
        pages = []
        for name in ("index.html", html.ALL_METHODS_PAGE):
            with open(os.path.join(out, name), encoding="utf-8") as f:
                pages.append(f.read())
        return pages[0], pages[1], sorted(os.listdir(out))


def images(page):
    return re.findall(r'<img src="([^"]+)"', page)


class FirstScreen(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        report = syn.make_report()
        del report["stability"]  # figures of no interest here: a faster test
        cls.index, cls.every, cls.files = written_pages(report)

    def test_the_answer_figure_is_written_and_shown_before_any_definition(self):
        self.assertIn(answer.FIGURE, self.files)
        first_paragraph = self.index.index("<p>")
        self.assertIn("keeping R on SO(3) pays on", self.index[first_paragraph:self.index.index("</p>")])
        figure = self.index.index(f'<img src="{answer.FIGURE}"')
        self.assertEqual(images(self.index)[0], answer.FIGURE)
        self.assertLess(first_paragraph, figure)
        self.assertLess(figure, self.index.index(DEFINITIONS))
        self.assertLess(figure, self.index.index('<h2 id="contents">'))

    def test_the_summary_shows_the_figure_right_after_the_answer(self):
        lines = [line for line in summary.summary_markdown(syn.make_report()).splitlines() if line.strip()]
        start = next(i for i, line in enumerate(lines) if not line.startswith("#"))
        self.assertTrue(lines[start].startswith("**Where R feeds back"))
        self.assertEqual(lines[start + 1], f"![{answer.CAPTION}]({answer.FIGURE})")
        self.assertTrue(lines[start + 2].startswith(DEFINITIONS))

    def test_captions_are_sentences_not_file_names(self):
        for page in (self.index, self.every):
            figures_ = re.findall(r'<img src="([^"]+)"[^>]*><figcaption>(.*?)</figcaption>', page)
            self.assertEqual(len(figures_), len(images(page)))
            for name, text in figures_:
                with self.subTest(figure=name):
                    self.assertNotIn(".png", text)
                    self.assertNotIn(name[:-4], text.replace(" ", "-"))
                    self.assertGreaterEqual(len(text.split()), 12)
                    self.assertTrue(text.endswith("."))
        self.assertNotIn("no description", captions.caption("convergence-plane.png"))
        self.assertNotIn("x.png", captions.caption("x.png"))

    def test_every_method_charts_are_on_their_own_page(self):
        every = [n for n in self.files if n.startswith("work-precision-") and "-best-" not in n]
        self.assertEqual(len(every), len(syn.SCENES))
        self.assertFalse(set(every) & set(images(self.index)))
        self.assertEqual(sorted(images(self.every)), every)
        self.assertIn(f'<a href="{html.ALL_METHODS_PAGE}">', self.index)
        self.assertIn('<a href="index.html">', self.every)
        # after the answer, the best of each family comes first
        shown = images(self.index)
        self.assertTrue(shown[1].startswith("work-precision-best-"), shown)


def legend_texts(fig):
    return [[t.get_text() for t in ax.get_legend().get_texts()] for ax in fig.axes if ax.get_legend()]


class ConvergenceLegends(unittest.TestCase):
    def convergence(self, report):
        return figures.convergence(report, SCENE, style.Palette({n: f[0] for n, f in syn.FIXED.items()}))

    def test_every_order_has_its_interval_and_verdict(self):
        report = syn.make_report()
        fig = self.convergence(report)
        orders = {o["integrator"]: o for o in report["orders"] if o["scene"] == SCENE}
        self.assertEqual(len(legend_texts(fig)), len(syn.COMPONENTS))  # a panel per component the report lists
        for texts, component in zip(legend_texts(fig), syn.COMPONENTS):
            self.assertEqual(len(texts), len(syn.FIXED))
            for text in texts:
                name = text.split()[0]
                o = orders[name]
                with self.subTest(label=text):
                    self.assertIn(f"{name}  p = {o['observed'][component]:.2f} ± {o['ci95'][component]:.2f}, "
                                  f"{o['verdict'][component]}", text)
        # the planted verdict, so the check can tell verdicts apart
        self.assertIn("gsl-rk4  p = 3.00 ± 0.05, lower", legend_texts(fig)[0])

    def test_an_interval_low_high_and_a_missing_one(self):
        report = copy.deepcopy(syn.make_report())
        for o in report["orders"]:
            if o["scene"] == SCENE and o["integrator"] == "rk4":
                o["ci95"]["contact"] = [3.99, 4.03]
            if o["scene"] == SCENE and o["integrator"] == "rkmk4":
                del o["ci95"]
        contact = legend_texts(self.convergence(report))[0]
        self.assertIn("rk4  p = 4.00 [3.99, 4.03], as declared", contact)
        # no interval: no order shown, only the verdict
        self.assertIn("rkmk4  p: no interval, as declared", contact)
        self.assertFalse([t for t in contact if re.search(r"p = \d+\.\d\d(?! (±|\[))", t)], contact)


if __name__ == "__main__":
    unittest.main()

"""The regime border's rules (analysis/crossover.py) on synthetic data whose
answers are known: the tie rule, the logistic crossover of outcomes laid
out symmetrically about a known point, its interval, and the held-out
check's counting."""
import math
import unittest

from analysis import crossover


def ratio(median, low=None, high=None, repeats=3, bound=""):
    return (median, median if low is None else low, median if high is None else high, repeats, bound)


class Outcome(unittest.TestCase):
    def test_a_range_that_holds_one_is_a_tie(self):
        self.assertEqual(crossover.outcome(ratio(0.91, 0.88, 1.34)), crossover.TIE)
        self.assertEqual(crossover.outcome(ratio(1.2, 1.0, 1.3)), crossover.TIE)  # 1 on the edge
        self.assertEqual(crossover.outcome(ratio(1.2, 1.01, 1.3)), crossover.LIE)
        self.assertEqual(crossover.outcome(ratio(0.5, 0.4, 0.99)), crossover.FLAT)

    def test_one_repeat_has_no_range_and_a_bound_or_nan_no_outcome(self):
        self.assertEqual(crossover.outcome(ratio(0.99, repeats=1)), crossover.FLAT)
        self.assertIsNone(crossover.outcome(ratio(2.0, bound="≥")))
        self.assertIsNone(crossover.outcome(ratio(math.nan)))


class Predictor(unittest.TestCase):
    def test_the_rates_ratio_and_a_plane(self):
        self.assertAlmostEqual(crossover.predictor({"omega0": 6.0, "bowl_frequency": 2.0}), 3.0)
        self.assertEqual(crossover.predictor({"omega0": 6.0, "bowl_frequency": 0.0}), math.inf)
        self.assertTrue(math.isnan(crossover.predictor({"scene": "an older report"})))


def outcomes(xs, lie_above, per_cell=3, swapped=()):
    """[(cell, X, outcome)]: per_cell targets per cell, LIE above lie_above, FLAT below; the (cell, target)
    pairs in swapped take the other side (the overlap a border zone has)."""
    out = []
    for i, x in enumerate(xs):
        for k in range(per_cell):
            lie = (x > lie_above) != ((i, k) in swapped)
            out.append((f"cell{i}", x, crossover.LIE if lie else crossover.FLAT))
    return out


class Fit(unittest.TestCase):
    # symmetric about 2 on a log scale
    XS = (0.25, 0.5, 1, 4, 8, 16)

    def test_outcomes_symmetric_about_a_point_cross_there(self):
        result = crossover.fit(outcomes(self.XS, 2.0))
        self.assertAlmostEqual(result["x_star"], 2.0, places=9)
        self.assertGreater(result["slope"], 0)
        self.assertEqual((result["points"], result["cells"]), (18, 6))
        self.assertLessEqual(result["low"], result["x_star"])
        self.assertGreaterEqual(result["high"], result["x_star"])
        # overlap mirrored about 2: the same centre, a flatter curve and a wider interval
        mixed = crossover.fit(outcomes(self.XS, 2.0, swapped={(2, 0), (3, 0)}))
        self.assertAlmostEqual(mixed["x_star"], 2.0, places=9)
        self.assertLess(mixed["slope"], result["slope"])
        self.assertLess(mixed["low"], 2.0)
        self.assertGreater(mixed["high"], 2.0)
        self.assertEqual(mixed, crossover.fit(outcomes(self.XS, 2.0, swapped={(2, 0), (3, 0)})))  # seeded

    def test_the_fit_maximises_the_penalised_likelihood(self):
        points = outcomes(self.XS, 2.0, swapped={(1, 1), (2, 0), (4, 2)})
        result = crossover.fit(points)
        lx = [math.log10(x) for _, x, _ in points]
        won = [1.0 if o == crossover.LIE else 0.0 for _, _, o in points]

        def objective(a, b):
            return sum(w * (a + b * t) - math.log1p(math.exp(a + b * t)) for t, w in zip(lx, won)) \
                - 0.5 * crossover.RIDGE * b * b
        best = objective(result["intercept"], result["slope"])
        for da, db in ((1e-3, 0), (-1e-3, 0), (0, 1e-3), (0, -1e-3)):
            self.assertLess(objective(result["intercept"] + da, result["slope"] + db), best)
        self.assertAlmostEqual(result["x_star"], 10.0 ** (-result["intercept"] / result["slope"]))

    def test_a_falling_or_one_sided_or_constant_x_has_no_crossover(self):
        falling = crossover.fit([(c, x, crossover.FLAT if o == crossover.LIE else crossover.LIE)
                                 for c, x, o in outcomes(self.XS, 2.0)])
        self.assertTrue(math.isnan(falling["x_star"]))
        self.assertTrue(math.isnan(falling["low"]))
        self.assertIsNone(crossover.fit(outcomes(self.XS, 0.1)))           # the Lie side wins everywhere
        self.assertIsNone(crossover.fit(outcomes((3.0, 3.0), 2.0, swapped={(0, 0)})))  # one X: no slope
        self.assertIsNone(crossover.fit(outcomes((3.0,), 2.0)))

    def test_ties_infinite_x_and_no_outcome_stay_out_of_the_fit(self):
        points = outcomes(self.XS, 2.0) + [("plane", math.inf, crossover.FLAT), ("tie", 2.0, crossover.TIE),
                                           ("bound", 2.0, None)]
        result = crossover.fit(points)
        self.assertAlmostEqual(result["x_star"], 2.0, places=9)
        self.assertEqual(result["cells"], 6)


class Check(unittest.TestCase):
    def test_predictions_against_outcomes_with_ties_and_planes(self):
        result = {"x_star": 2.0, "low": 1.5, "high": 2.5}
        entries = [({"omega0": 1.0, "bowl_frequency": 5.0}, ratio(0.7, 0.6, 0.8)),    # flat predicted, flat
                   ({"omega0": 30.0, "bowl_frequency": 2.0}, ratio(1.5, 1.3, 1.6)),   # Lie, Lie
                   ({"omega0": 8.0, "bowl_frequency": 0.0}, ratio(0.8, 0.7, 0.9)),    # plane: Lie, flat: wrong
                   ({"omega0": 3.0, "bowl_frequency": 1.0}, ratio(1.0, 0.9, 1.1)),    # a tie: not counted
                   ({"omega0": 3.0, "bowl_frequency": 1.0}, ratio(3.0, bound="≥"))]  # a bound: not counted
        rows = crossover.check(entries, result)
        self.assertEqual([r[2] for r in rows], [crossover.FLAT, crossover.LIE, crossover.LIE, crossover.LIE,
                                                crossover.LIE])
        self.assertEqual([r[3] for r in rows], [crossover.FLAT, crossover.LIE, crossover.FLAT, crossover.TIE, None])
        self.assertEqual([r[4] for r in rows], [True, True, False, None, None])
        self.assertEqual(rows[2][1], math.inf)

    def test_no_crossover_predicts_nothing(self):
        rows = crossover.check([({"omega0": 1.0, "bowl_frequency": 5.0}, ratio(0.7, 0.6, 0.8))],
                               {"x_star": math.nan, "low": math.nan, "high": math.nan})
        self.assertEqual((rows[0][2], rows[0][4]), (None, None))
        self.assertIsNone(crossover.predict(1.0, None))


if __name__ == "__main__":
    unittest.main()

"""The formula evaluator: agrees with NumPy, rejects what is not in the language."""
import ast
import glob
import json
import os
import unittest

import numpy as np

from analysis import formula

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class FormulaAgreesWithNumpy(unittest.TestCase):
    def setUp(self):
        grid = np.meshgrid(np.linspace(-0.9, 0.9, 13), np.linspace(-0.6, 0.7, 11))
        self.x, self.y = grid

    def check(self, text, expected, params=None, rtol=1e-14):
        got = formula.Landscape(text, params)(self.x, self.y)
        np.testing.assert_allclose(got, expected, rtol=rtol, atol=1e-15, err_msg=text)

    def test_scene_landscapes(self):
        x, y = self.x, self.y
        self.check("cos(x*pi + pi)/10 - y/10", np.cos(x * np.pi + np.pi) / 10 - y / 10)
        with np.errstate(invalid="ignore"):  # the bowl is undefined in the grid's corners: NaN both sides
            bowl = 1.0 - np.sqrt(1.0 - x ** 2 - y ** 2)
        self.check("rho - sqrt(rho^2 - x^2 - y^2)", bowl, {"rho": 1.0})
        self.check("a*(x^2 + y^2) + b*sin(3*x)*cos(2*y)",
                   0.1 * (x ** 2 + y ** 2) + 0.02 * np.sin(3 * x) * np.cos(2 * y), {"a": 0.1, "b": 0.02})
        self.check("h*exp(-((x - 1)^2 + (y - 0.5)^2)/w)", 0.15 * np.exp(-((x - 1) ** 2 + (y - 0.5) ** 2) / 0.4),
                   {"h": 0.15, "w": 0.4})

    def test_precedence_and_associativity(self):
        x, y = self.x, self.y
        self.check("-x^2", -(x ** 2))                   # unary minus binds looser than ^
        self.check("2^3^2 + 0*x", np.full_like(x, 512.0))  # right-associative
        self.check("2**-x", 2.0 ** -x)                  # ** is ^, and a signed exponent is allowed
        self.check("x - y - 1", (x - y) - 1)            # left-associative
        self.check("x / y / 2", (x / y) / 2)
        self.check("1e-3*x + .5*y + 2.5E+1", 1e-3 * x + 0.5 * y + 25.0)
        self.check("atan2(y, x) + hypot(x, y) - e*tanh(x)", np.arctan2(y, x) + np.hypot(x, y) - np.e * np.tanh(x))
        self.check("asin(x) + acos(y) + atan(x*y) + sinh(x) + cosh(y) + tan(x) + log(2 + x)",
                   np.arcsin(x) + np.arccos(y) + np.arctan(x * y) + np.sinh(x) + np.cosh(y) + np.tan(x)
                   + np.log(2 + x))

    def test_long_sums_do_not_overflow_the_stack(self):
        self.check("x" + " + x" * 5000, 5001 * self.x, rtol=1e-12)

    def test_constant_formula_has_the_grid_shape(self):
        self.assertEqual(formula.Landscape("0")(self.x, self.y).shape, self.x.shape)

    def test_outside_the_domain_is_nan_not_an_error(self):
        z = formula.Landscape("sqrt(1 - x^2 - y^2)")(np.array([2.0]), np.array([0.0]))
        self.assertTrue(np.isnan(z[0]))

    def test_every_shipped_scene_parses(self):
        files = glob.glob(os.path.join(ROOT, "problems", "scenes", "*.json"))
        for path in files:
            with open(path, encoding="utf-8") as f:
                scene = json.load(f)
            with self.subTest(scene=os.path.basename(path)):
                z = formula.Landscape(scene["landscape"], scene.get("params"))(np.array([0.1]), np.array([0.2]))
                self.assertTrue(np.isfinite(z).all())


class FormulaRejects(unittest.TestCase):
    def rejects(self, text, fragment, column=None, params=None):
        with self.assertRaises(formula.FormulaError) as caught:
            formula.parse(text, params)
        self.assertIn(fragment, str(caught.exception))
        if column is not None:
            self.assertEqual(caught.exception.column, column)
        return caught.exception

    def test_python_code_is_not_a_formula(self):
        self.rejects("__import__('os')", "unknown function '__import__'", column=1)
        self.rejects("x.__class__", "unexpected character", column=2)
        self.rejects("open('f')", "unknown function 'open'", column=1)
        self.rejects("x if y else 1", "expected an operator before 'if'", column=3)

    def test_non_smooth_functions_say_why(self):
        error = self.rejects("abs(x)", "abs is not smooth", column=1)
        self.assertIn("continuous second derivatives", str(error))
        self.assertIn("sqrt(x^2 + eps)", str(error))
        self.rejects("1 + max(x, y)", "max is not smooth", column=5)
        self.rejects("floor(x)", "floor is not smooth")

    def test_syntax_errors_name_the_column(self):
        self.rejects("x +", "expected an operand after '+'", column=4)
        self.rejects("sin(x", "missing ')'", column=4)
        self.rejects("x)", "no matching '('", column=2)
        self.rejects("sin x", "sin is a function", column=1)
        self.rejects("hypot(x)", "hypot takes 2 arguments, got 1", column=1)
        self.rejects("1.2.3", "malformed number", column=1)
        self.rejects("Sin(x)", "did you mean 'sin'?", column=1)
        self.rejects("q*x", "unknown name 'q'", column=1)
        self.rejects("a(x)", "'a' is not a function", params={"a": 1.0})
        self.rejects("(" * 300 + "x" + ")" * 300, "nests deeper than")

    def test_bad_params(self):
        self.rejects("x", "hides a built-in name", params={"pi": 3.0})
        self.rejects("x", "must be a finite number", params={"a": "1"})

    def test_source_never_calls_eval_or_exec(self):
        with open(formula.__file__, encoding="utf-8") as f:
            tree = ast.parse(f.read())
        called = {node.func.id for node in ast.walk(tree)
                  if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)}
        self.assertFalse(called & {"eval", "exec", "compile", "__import__"})


if __name__ == "__main__":
    unittest.main()

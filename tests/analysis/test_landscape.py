"""`rollbench landscape` and the analysis' use of it: heights against the
closed forms of shipped scenes, NaN where a formula is undefined, bad input
refused with exit 2 naming the option. Needs the built rollbench (CTest
runs this after the build); a missing binary fails, it is never skipped."""
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np

from analysis import landscape

ROLLBENCH = landscape.DEFAULT_ROLLBENCH


def rollbench(*args):
    return subprocess.run([ROLLBENCH, "landscape", *args], capture_output=True, text=True, timeout=60)


class LandscapeGrid(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not os.access(ROLLBENCH, os.X_OK):
            raise AssertionError(f"no rollbench at {ROLLBENCH}: build it first (cmake --build build/release "
                                 "--target rollbench) or set RB_ROLLBENCH")

    def test_shipped_scenes_match_their_closed_forms(self):
        x, y, z = landscape.grid("valley-sideways", 13, 11, (-0.9, 0.9, -0.6, 0.7), ROLLBENCH)
        self.assertEqual(z.shape, (11, 13))
        np.testing.assert_allclose(x[0], np.linspace(-0.9, 0.9, 13), rtol=0, atol=1e-15)  # x runs fastest
        np.testing.assert_allclose(y[:, 0], np.linspace(-0.6, 0.7, 11), rtol=0, atol=1e-15)
        np.testing.assert_allclose(z, np.cos(x * np.pi + np.pi) / 10 - y / 10, rtol=1e-14, atol=1e-16)
        x, y, z = landscape.grid("gaussian-hills", 7, 5, (-3, 3, -3, 3), ROLLBENCH)
        q, h, w, d = 0.05, 0.15, 0.4, 0.1
        expected = (q * (x ** 2 + y ** 2) + h * np.exp(-((x - 1) ** 2 + (y - 0.5) ** 2) / w)
                    + h * np.exp(-((x + 0.8) ** 2 + (y - 1) ** 2) / w)
                    + h * np.exp(-((x - 0.2) ** 2 + (y + 1) ** 2) / w)
                    - d * np.exp(-(x ** 2 + y ** 2) / (2 * w)))
        np.testing.assert_allclose(z, expected, rtol=1e-13, atol=1e-16)

    def test_undefined_points_are_nan(self):
        # the bowl z = 1 - sqrt(1 - x^2 - y^2) has no value beyond radius 1
        x, y, z = landscape.grid("bowl-3d", 5, 5, (-2, 2, -2, 2), ROLLBENCH)
        inside = x ** 2 + y ** 2 <= 1
        self.assertTrue(np.isnan(z[~inside]).all())
        np.testing.assert_allclose(z[inside], 1 - np.sqrt(1 - x[inside] ** 2 - y[inside] ** 2), rtol=1e-14)

    def test_a_scene_file_with_params(self):
        with tempfile.TemporaryDirectory() as tmp:
            with open(os.path.join(landscape.ROOT, "problems", "scenes", "saddle.json"), encoding="utf-8") as f:
                scene = json.load(f)
            scene["params"] = {"a": 0.5}
            path = os.path.join(tmp, "steep-saddle.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(scene, f)
            x, y, z = landscape.grid(path, 4, 3, (-1, 1, -1, 1), ROLLBENCH)
        np.testing.assert_allclose(z, 0.5 * (x ** 2 - y ** 2), rtol=1e-15, atol=1e-16)

    def test_bad_input_exits_2_naming_the_option(self):
        cases = [
            (["valley-sideways", "--grid", "3"], "'grid': expected NX,NY (two integers), got '3'"),
            (["valley-sideways", "--grid", "1,5", "--domain=0,1,0,1"], "'grid': each of NX,NY must be an integer"),
            (["valley-sideways", "--grid", "3,3", "--domain=0,1,0"], "'domain': expected xmin,xmax,ymin,ymax"),
            (["valley-sideways", "--grid", "3,3", "--domain=1,0,0,1"], "'domain': expected xmin < xmax"),
            (["plane", "--grid", "3,3"], "'domain': scene 'plane' has no domain"),
            (["no-such-scene", "--grid", "3,3"], "'scene': unknown scene 'no-such-scene'"),
            (["valley-sideways"], "--grid is required"),
        ]
        for args, message in cases:
            with self.subTest(args=args):
                done = rollbench(*args)
                self.assertEqual(done.returncode, 2, done.stderr)
                self.assertIn(message, done.stderr)
                self.assertEqual(done.stdout, "")

    def test_a_bad_formula_is_rollbenchs_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bad.json")
            with open(os.path.join(landscape.ROOT, "problems", "scenes", "saddle.json"), encoding="utf-8") as f:
                scene = json.load(f)
            scene["landscape"] = "a*(x^2 - y^2) +* 1"
            with open(path, "w", encoding="utf-8") as f:
                json.dump(scene, f)
            with self.assertRaisesRegex(landscape.LandscapeError, "'landscape' column"):
                landscape.grid(path, 3, 3, (-1, 1, -1, 1), ROLLBENCH)

    def test_a_missing_binary_is_named(self):
        with self.assertRaisesRegex(landscape.LandscapeError, "no rollbench at '/no/such/rollbench'"):
            landscape.grid("plane", 3, 3, (0, 1, 0, 1), "/no/such/rollbench")


if __name__ == "__main__":
    unittest.main()

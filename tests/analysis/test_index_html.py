"""index.html in a real headless browser (Debian's chromium): every figure
plot.py wrote is on the page and loads; a missing image is seen as broken,
so the check can fail. chromium comes from scripts/install-deps.sh; without
it this test fails, it is never skipped."""
import os
import re
import shutil
import signal
import subprocess
import tempfile
import unittest

from analysis import html, plot
from tests.analysis import synthetic as syn

TIMEOUT_S = 120


def render(page_path, profile_dir):
    """The DOM after load, as chromium --dump-dom prints it; chromium is stopped by its process id."""
    chromium = shutil.which("chromium")
    if chromium is None:
        raise AssertionError("chromium is not installed: run scripts/install-deps.sh (Debian package 'chromium')")
    command = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--no-first-run", f"--user-data-dir={profile_dir}",
               "--virtual-time-budget=10000", "--dump-dom", "file://" + os.path.abspath(page_path)]
    # its own session, so that the browser and its helper processes can be stopped together
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                            start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise AssertionError(f"chromium did not finish within {TIMEOUT_S} s") from None
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    if proc.returncode != 0:
        raise AssertionError(f"chromium exited with {proc.returncode}")
    return out


def image_states(dom):
    """{src: data-state} of every <img> in the dumped DOM."""
    out = {}
    for tag in re.findall(r"<img\b[^>]*>", dom):
        src = re.search(r'src="([^"]+)"', tag)
        state = re.search(r'data-state="([^"]+)"', tag)
        out[src.group(1) if src else "?"] = state.group(1) if state else "unmarked"
    return out


class IndexPageInChromium(unittest.TestCase):
    def test_every_figure_loads(self):
        with tempfile.TemporaryDirectory() as tmp:
            report = syn.subset(syn.make_report(), "plane", ("rk4", "rkmk4", "odeint-dopri5-adaptive"))
            del report["stability"]
            ball = os.path.join(tmp, "ball")
            os.makedirs(ball)
            for name, growth in syn.BALL_GROWTH.items():
                syn.ball_csv(os.path.join(ball, f"{name}.csv"), growth)
            out = os.path.join(tmp, "plots")
            plot.write_all(report, out, plot.Options(ball=ball), log=lambda _: None)
            pngs = sorted(n for n in os.listdir(out) if n.endswith(".png"))
            self.assertGreaterEqual(len(pngs), 6)
            dom = render(os.path.join(out, "index.html"), os.path.join(tmp, "profile"))
            every = render(os.path.join(out, html.ALL_METHODS_PAGE), os.path.join(tmp, "profile"))
            # the every-method charts on their own page, every other figure on index.html
            self.assertEqual(image_states(dom), {n: "loaded" for n in pngs if not html.all_methods(n)})
            self.assertEqual(image_states(every), {n: "loaded" for n in pngs if html.all_methods(n)})
            self.assertIn("Same tableau, flat vs Lie", dom)

    def test_a_missing_image_is_seen_as_broken(self):
        with tempfile.TemporaryDirectory() as tmp:
            page = os.path.join(tmp, "index.html")
            with open(page, "w", encoding="utf-8") as f:
                f.write(html.index_html(["not-there.png"], "# empty\n"))
            dom = render(page, os.path.join(tmp, "profile"))
            self.assertEqual(image_states(dom), {"not-there.png": "broken"})


if __name__ == "__main__":
    unittest.main()

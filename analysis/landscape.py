"""Landscape values on a grid from `rollbench landscape` (the C++ scene
loader and formula, so the analysis never parses a formula itself)."""
import csv
import io
import os
import subprocess

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# RB_ROLLBENCH: another build's binary (CTest sets it to the one it built)
DEFAULT_ROLLBENCH = os.environ.get("RB_ROLLBENCH") or os.path.join(ROOT, "build", "release", "rollbench")
TIMEOUT_S = 60


class LandscapeError(RuntimeError):
    """rollbench could not give the grid; the message says why (its own error text)."""


def grid(scene, nx, ny, domain, rollbench=DEFAULT_ROLLBENCH):
    """(X, Y, Z) arrays of shape (ny, nx) over domain = (xmin, xmax, ymin, ymax); Z is NaN where f is undefined.

    scene: a shipped scene's name or a scene JSON path.
    """
    box = ",".join(repr(float(v)) for v in domain)
    command = [rollbench, "landscape", scene, "--grid", f"{nx},{ny}", f"--domain={box}"]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT_S, check=False)
    except FileNotFoundError:
        raise LandscapeError(f"no rollbench at '{rollbench}' (build it, or pass --rollbench PATH)") from None
    except subprocess.TimeoutExpired:
        raise LandscapeError(f"'{' '.join(command)}' took longer than {TIMEOUT_S} s") from None
    if done.returncode != 0:
        raise LandscapeError(done.stderr.strip() or f"rollbench landscape exited with {done.returncode}")
    rows = list(csv.reader(io.StringIO(done.stdout)))
    if not rows or rows[0] != ["x", "y", "z"] or len(rows) != nx * ny + 1:
        raise LandscapeError(f"unexpected output of '{' '.join(command)}' ({len(rows)} lines)")
    values = np.array(rows[1:], dtype=float)
    shape = (ny, nx)  # x runs fastest
    return values[:, 0].reshape(shape), values[:, 1].reshape(shape), values[:, 2].reshape(shape)

""""The ball deforms": the unit sphere mapped by each method's R at a few
times of a long run. R of a flat method drifts off SO(3), so its image of
the sphere becomes an ellipsoid; a Lie-group method's R stays a rotation,
so its ball stays round."""
import os

import numpy as np

from analysis.figures import NothingToPlot, new_figure
from analysis.figures_overview import read_trajectory

R_COLUMNS = tuple(f"r{i}{j}" for i in range(3) for j in range(3))
TIMES = 4  # panels per method: the start, two in between, the end
SPHERE = (np.linspace(0, 2 * np.pi, 25), np.linspace(0, np.pi, 13))


def rotations(path):
    """(t, R[k]) from a trajectory CSV."""
    data = read_trajectory(path, ("t",) + R_COLUMNS)
    r = np.stack([data[c] for c in R_COLUMNS], axis=1).reshape(-1, 3, 3)
    return data["t"], r


def stretch(r):
    """Largest over smallest singular value of R: 1 for a rotation."""
    s = np.linalg.svd(r, compute_uv=False)
    return s[0] / s[-1] if s[-1] > 0 else np.inf


def _draw(ax, r, colour, lim):
    u, v = np.meshgrid(*SPHERE)
    points = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])
    x, y, z = np.einsum("ij,jab->iab", r, points)
    ax.plot_wireframe(x, y, z, color=colour, linewidth=0.5)
    for a in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        a(-lim, lim)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()


def trajectory_files(trajectory_dir, methods):
    """[(method, label, path)]: <method>.csv, or <method>-h<step>.csv labelled with its step."""
    found = []
    names = sorted(os.listdir(trajectory_dir)) if os.path.isdir(trajectory_dir) else []
    for method in methods:
        for name in names:
            stem = name[:-4]
            if name.endswith(".csv") and (stem == method or stem.startswith(method + "-h")):
                label = method if stem == method else f"{method}, h = {stem[len(method) + 2:]} s"
                found.append((method, label, os.path.join(trajectory_dir, name)))
                break
    return found


def ball_deforms(trajectory_dir, methods=("euler", "rk4", "rkmk4")):
    """A row per method with a trajectory in trajectory_dir (see trajectory_files), a column per time."""
    found = trajectory_files(trajectory_dir, methods)
    if not found:
        raise NothingToPlot(f"no trajectory CSV of {', '.join(methods)} in {trajectory_dir}")
    colours = {"euler": "#1f77b4", "rk4": "#17becf", "rkmk4": "#d62728"}
    rows = []
    for method, label, path in found:
        try:
            t, r = rotations(path)
        except (ValueError, StopIteration) as e:  # safe_files.InputFileError included: a FIFO, /dev/zero
            raise NothingToPlot(f"cannot read {path}: {e or 'no header'}") from None
        picks = np.unique(np.linspace(0, t.size - 1, TIMES).round().astype(int))
        rows.append((method, label, t, r, picks))
    # one scale for every panel, so that a ball that grows or shrinks is seen to
    lim = max([1.0] + [float(np.linalg.norm(r[k], 2)) for _, _, _, r, picks in rows for k in picks])
    fig = new_figure(3.0 * TIMES, 3.1 * len(found))
    for row, (method, label, t, r, picks) in enumerate(rows):
        for col, k in enumerate(picks):
            ax = fig.add_subplot(len(found), TIMES, row * TIMES + col + 1, projection="3d")
            _draw(ax, r[k], colours.get(method, "#555555"), lim)
            defect = np.linalg.norm(r[k].T @ r[k] - np.eye(3))
            ax.set_title(f"{label}, t = {t[k]:.4g} s\naxes ratio {stretch(r[k]):.3f}, "
                         f"‖RᵀR − I‖ = {defect:.2g}", fontsize=8)
    fig.suptitle("the ball as R maps the unit sphere: R off SO(3) makes it an ellipsoid\n"
                 f"(trajectories in {os.path.basename(os.path.normpath(trajectory_dir))}/)", fontsize=11)
    fig.subplots_adjust(wspace=0.0, hspace=0.25)
    return fig

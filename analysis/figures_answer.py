"""answer.png: the first screen's figure. One row per scene where R feeds
back: the flat/Lie wall-time ratio the answer sentences give (answer.py),
its bar the timed repeats' lowest–highest, every counted pair × target as
a small grey mark, and a line at 1 so a scene the flat method wins is seen
left of it."""
import math

import numpy as np
from matplotlib.ticker import FuncFormatter

from analysis import answer, findings
from analysis import report as rp
from analysis import style
from analysis.figures import NothingToPlot, new_figure

PAYS = style.FAMILY_COLOURS["rkmk"]  # the Lie side's hue: keeping R on SO(3) pays
LOSES = style.FAMILY_COLOURS["rk"]   # the flat side's hue: the flat method wins
CELL = "#9a9a9a"


def _row(ax, y, cells, median, low, high):
    # the cells a little above and below the row, so that they do not hide the scene's own marker
    ratios = sorted((r for *_, r in cells), key=lambda r: r[0])
    offsets = np.linspace(-0.22, 0.22, len(ratios)) if len(ratios) > 1 else [0.22]
    for dy, (m, lo, hi, *_rest) in zip(offsets, ratios):
        ax.plot([lo, hi], [y + dy] * 2, color=CELL, linewidth=0.8, zorder=1)
        ax.plot(m, y + dy, marker="o", markersize=3, color=CELL, zorder=1)
    colour = PAYS if median > 1 else LOSES
    ax.plot([low, high], [y, y], color=colour, linewidth=3.5, solid_capstyle="butt", zorder=3)
    # hollow: the repeats straddle 1, so the side is within the timing noise
    ax.plot(median, y, marker="D", markersize=8, color=colour, zorder=4,
            markerfacecolor="white" if answer.straddles(low, high) else colour)


def answer_figure(report, metric=rp.DEFAULT_METRIC):
    """The flat/Lie ratio per scene where R feeds back, against 1 (log scale)."""
    answers = [(scene, cells) for scene, cells in findings.scene_answers(report, metric) if cells]
    if not answers:
        raise NothingToPlot("no scene where R feeds back has a measured (not bounded) flat/Lie ratio")
    # the largest ratio on top: the scenes where the flat method wins gather at the bottom
    rows = sorted(((scene, cells, *answer.scene_ratio(cells)) for scene, cells in answers), key=lambda r: r[2])
    fig = new_figure(9, 1.5 + 0.42 * len(rows))
    ax = fig.subplots()
    values = [v for _, cells, *_ in rows for *_, r in cells for v in r[:3] if math.isfinite(v) and v > 0]
    lo, hi = min(values + [1.0]), max(values + [1.0])
    span = max(math.log10(hi / lo), 0.2)
    ax.set_xscale("log")
    ax.set_xlim(lo / 10 ** (0.12 * span), hi * 10 ** (0.12 * span))
    ax.axvspan(ax.get_xlim()[0], 1, color=LOSES, alpha=0.06, linewidth=0, zorder=0)
    ax.axvspan(1, ax.get_xlim()[1], color=PAYS, alpha=0.06, linewidth=0, zorder=0)
    ax.axvline(1, color="black", linewidth=1.2, zorder=2)
    for y, (scene, cells, median, low, high) in enumerate(rows):
        _row(ax, y, cells, median, low, high)
        # the number the sentences give, beside the axes, so the figure reads without the text
        ax.text(1.01, y, f"{median:.2f} [{low:.2f}–{high:.2f}]", transform=ax.get_yaxis_transform(), va="center",
                fontsize=9, color=PAYS if median > 1 else LOSES)
    ax.set_yticks(range(len(rows)), [r[0] for r in rows], fontsize=9)
    ax.set_ylim(-0.6, len(rows) - 0.4)
    ax.text(0.01, 1.01, "← the flat method is cheaper", transform=ax.transAxes, ha="left", va="bottom",
            fontsize=8.5, color=LOSES)
    ax.text(0.99, 1.01, "the Lie method is cheaper →", transform=ax.transAxes, ha="right", va="bottom",
            fontsize=8.5, color=PAYS)
    ax.set_xlabel(f"flat wall time / Lie wall time to the same {metric} error over the run (log scale)")
    # plain numbers (0.8, 1, 2): a ratio reads as a factor, not as a power of ten
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    ax.xaxis.set_major_formatter(plain)
    ax.xaxis.set_minor_formatter(plain if span < 1 else FuncFormatter(lambda v, _: ""))
    ax.tick_params(axis="x", which="both", labelsize=8.5)
    ax.grid(True, axis="x", which="both", alpha=0.25)
    ax.set_title("Does keeping R on SO(3) pay? Per scene where R feeds back", fontsize=10, pad=16)
    return fig

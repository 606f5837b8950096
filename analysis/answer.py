"""The first screen's answer: does keeping R on SO(3) pay, where, and by how
much. Two or three sentences and one number per scene where R feeds back,
from the cells the findings count (findings.aggregate_cells: each Lie
method once against its cheapest geometry twin, per target; no
bounds, no exact scenes). answer.png (figures_answer.py) draws the same
numbers."""
import math

FIGURE = "answer.png"


def scene_ratio(cells):
    """(median, low, high) of a scene: the median cell's flat/Lie ratio and its timed repeats' lowest–highest.

    The median cell is the upper one of an even count (the findings' median),
    so the number and its interval are one measured pair × target, not a mix.
    """
    ranked = sorted((r for *_, r in cells), key=lambda r: r[0])
    median, low, high = ranked[len(ranked) // 2][:3]
    return median, low, high


def measured(answers):
    """[(scene, median, low, high)] of the scenes with at least one counted cell ([(scene, cells)])."""
    return [(scene, *scene_ratio(cells)) for scene, cells in answers if cells]


def straddles(low, high):
    """The repeats put the ratio on both sides of 1: which side wins is within the timing noise."""
    return math.isfinite(low) and math.isfinite(high) and low <= 1 <= high and low < high


def _item(scene, median, low, high):
    spread = f"{median:.2f} [{low:.2f}–{high:.2f}]"
    return f"{scene} ({spread}, the repeats straddle 1)" if straddles(low, high) else f"{scene} ({spread})"


def lines(answers, metric="worst"):
    """The answer's sentences ([text, ""]); one sentence saying why when no scene has a counted ratio."""
    found = measured(answers)
    if not found:
        return ["**No scene where R feeds back has a measured flat/Lie ratio in this report**, so it does not say "
                "whether keeping R on SO(3) pays (no same-tableau pair reached a target without a bound, or no "
                "scene's reference marks R as feeding back).", ""]
    wins = [_item(*f) for f in found if f[1] > 1]
    loses = [_item(*f) for f in found if f[1] <= 1]
    text = (f"**Where R feeds back, keeping R on SO(3) pays on {len(wins)} of {len(found)} scenes**"
            + (f": {', '.join(wins)}." if wins else "."))
    text += f" The flat method wins on {', '.join(loses)}." if loses else " The flat method wins on none."
    text += (f" Each number is the flat method's wall time over the Lie method's to the same {metric} error over "
             "the run (above 1: the Lie method is cheaper; the median over same-tableau pairs and targets) with "
             "[lowest–highest] over the timed repeats; bounds (≤/≥) and scenes where the Lie method is exact are "
             "not counted.")
    return [text, ""]


CAPTION = ("Per scene where R feeds back, the flat/Lie wall-time ratio (large marker, its bar the lowest–highest "
           "over the timed repeats; small grey marks: every pair and target counted) against the line at 1: "
           "right of the line keeping R on SO(3) pays, left of it the flat method wins.")


def figure_lines():
    """summary.md's line for answer.png (index.html renders it as a figure with this caption)."""
    return [f"![{CAPTION}]({FIGURE})", ""]

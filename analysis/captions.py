"""One sentence under each figure of index.html and all-methods.html: what
it shows and how to read it, by the figure's file name (plot.py's names).
A name plot.py does not write still gets a sentence, never just its name."""
from analysis import answer

# (prefix, sentence with {scene} for the part of the name after the prefix); the longer prefix first
PER_SCENE = (
    ("work-precision-best-", "Accuracy against cost on {scene}, one line per family (its method with the lowest "
     "cost over the family's accuracy range): lower left is better, and the dotted lines are the accuracies the "
     "summary's cost tables read."),
    ("work-precision-", "Accuracy against wall time (left) and rhs-equivalents (right: evaluations of F, an "
     "implicit method's Jacobians and Newton passes included) on {scene}, "
     "every method: lower left is better; hollow markers are adaptive methods."),
    ("convergence-", "Each error component the report lists (a panel each) against step size on {scene}, "
     "log–log: a line parallel to its dashed guide has its declared order, and the legend gives each method's "
     "fitted order with its 95 % interval and the runner's verdict."),
    ("tolerance-", "Error against requested tolerance per adaptive method on {scene}: a line of slope 1 means "
     "the tolerance means what it says, and its height how far the error sits above or below it."),
    ("drift-", "Energy error and rotation defect on {scene}, against time over a long run (top) and against "
     "cost for each sweep run (bottom): flat is bounded, slope 1 linear growth, slope 2 quadratic."),
    ("horizon-", "Energy error (top) and rotation defect, then the relative error of each first integral the "
     "scene declares (Routh's, the Chaplygin ball's), each the largest per window, against time on {scene}, "
     "log–log: the legend's p is the fitted growth err ∝ tᵖ over the shaded window."),
    ("regime-", "Flat/Lie time ratio of the best twin pair (the same tableau, controller and norm) over the regime "
     "study's grid at an error of {scene}: blue cells are where keeping R on SO(3) pays (above 1), red where the "
     "flat method wins, and each cell names its ratio and cheapest method."),
)
WHOLE = {
    "horizon-cost.png": "The price of a bounded energy over the horizon study's runs: per scene, each method's "
                        "CPU seconds for the whole run against its largest energy error relative to the energy "
                        "scale; below the dotted line at 1e-6 the method kept the energy; a cross at the top is a "
                        "run that stopped.",
    answer.FIGURE: answer.CAPTION,
    "regime-border.png": "The regime map's border: the flat/Lie time ratio of every grid cell where R feeds back "
                         "against |ω0|/Ω, the ball's rotation rate over the bowl's frequency, with the fitted line, "
                         "the crossover x* where it is 1 (shaded: its 95 % interval) and the held-out scenes "
                         "(hollow: predicted wrong).",
    "stability.png": "Per fixed-step method and scene (left): the drift-limited step h*(T) at each horizon (one "
                     "fill each: the largest step whose run to T keeps the energy error and the rotation defect "
                     "within their bounds) and the blow-up step (red bar: the smallest step whose run stops, "
                     "passes a blow-up bound or grows exponentially); how each method's runs ended (right; grey "
                     "is ok, colours are the failures).",
    "scenes.png": "Each scene's landscape as shaded height contours, with the contact point's path where a "
                  "trajectory was given.",
    "ball-deforms.png": "The ball as each method's R maps the unit sphere, at a few times: a sphere means R is "
                        "still a rotation, an ellipsoid means R has left SO(3).",
    "ns-per-step.png": "Nanoseconds per step of each fixed-step method, one panel per scene, colour by family: "
                       "shorter bars are cheaper steps.",
}


def caption(name):
    """The sentence for figure file name (never the name itself)."""
    if name in WHOLE:
        return WHOLE[name]
    stem = name[:-4] if name.endswith(".png") else name
    for prefix, text in PER_SCENE:
        if stem.startswith(prefix):
            return text.format(scene=stem[len(prefix):])
    return f"A figure of this report ({stem.replace('-', ' ')}) that this page has no description for yet."

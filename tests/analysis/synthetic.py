"""Synthetic rollbench reports with known answers.

Every fixed-step error is exactly C * h^p and every cost exactly k / h, so a
test can compute what the analysis must print (orders, cost to accuracy)
from the model below instead of trusting the analysis' own output.
Adaptive runs follow error = a * tol^s and rhs_evals = k * tol^(-1/q).
"""
import copy
import math

import numpy as np

T_END = 2.0
HS = [2.0 ** -k for k in range(4, 10)]
TOLS = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
# error_max (the worst over the run) is this times the error at t_end, every component
ERROR_MAX_FACTOR = 1.5
SAMPLE_SPREAD = (1.00, 0.98, 1.03, 0.99, 1.01)  # timing noise, median exactly 1

# scene: (reference kind, reference error = the floor)
SCENES = {"plane": ("exact", 0.0), "valley-sideways": ("computed", 1e-12)}
# every error constant is multiplied by the scene's factor (a harder scene costs more)
SCENE_FACTOR = {"plane": 1.0, "valley-sideways": 3.0}

# name: family, order (contact), order (rotation), C (contact), C (rotation), stages, ns per rhs eval
FIXED = {
    "euler":             ("rk", 1, 1, 0.5, 0.2, 1, 80.0),
    "exp-euler":         ("rkmk", 1, 1, 0.3, 0.1, 1, 120.0),
    "rk4":               ("rk", 4, 4, 2.0, 9.0, 4, 80.0),
    "rkmk4":             ("rkmk", 4, 4, 2.0, 0.5, 4, 130.0),
    "rkmk4-seminar":     ("rkmk", 4, 3, 1.0, 0.3, 4, 125.0),
    "odeint-rk4":        ("odeint", 4, 4, 2.6, 1.3, 4, 90.0),
    "gsl-rk4":           ("gsl", 4, 4, 0.05, 0.05, 4, 100.0),
    # a same-tableau pair: equal contact error, the flat one's R is worse
    "odeint-fehlberg78": ("odeint", 8, 8, 200.0, 2000.0, 13, 90.0),
    "rkmk8":             ("rkmk", 8, 8, 200.0, 20.0, 13, 130.0),
}
# name: family, declared order, a, k (rhs = k * tol^(-1/q)), q, ns per rhs eval, s, rotation factor;
# error = a * tol^s (times the component's scale; rotation: times the rotation factor)
ADAPTIVE = {
    "odeint-dopri5-adaptive":     ("odeint", 5, 5.0, 40.0, 5.0, 95.0, 1.0, 8.0),
    "rkmk-dp54-adaptive":         ("rkmk", 5, 5.0, 40.0, 5.0, 140.0, 1.0, 0.5),
    "odeint-fehlberg78-adaptive": ("odeint", 8, 5.0, 60.0, 8.0, 95.0, 1.0, 8.0),
    "rkmk-f78-adaptive":          ("rkmk", 8, 0.5, 60.0, 8.0, 140.0, 1.0, 0.5),
    "gsl-rkf45-adaptive":         ("gsl", 5, 2.0, 60.0, 5.0, 105.0, 0.8, 0.5),
}
# (flat, Lie) pairs the summary must put side by side
PAIRS = [("rk4", "rkmk4"), ("odeint-fehlberg78", "rkmk8"),
         ("odeint-fehlberg78-adaptive", "rkmk-f78-adaptive"), ("odeint-dopri5-adaptive", "rkmk-dp54-adaptive")]
# the methods' MethodInfo tableau (the runner's facts, from which the analysis pairs them); Lie: family rkmk
TABLEAU = {"rk4": "rk4", "rkmk4": "rk4", "odeint-fehlberg78": "f78", "rkmk8": "f78",
           "odeint-fehlberg78-adaptive": "f78", "rkmk-f78-adaptive": "f78",
           "odeint-dopri5-adaptive": "dp54", "rkmk-dp54-adaptive": "dp54"}
# scenes where R feeds back (an anisotropic ball, with its moments)
INERTIA = {"valley-sideways": [0.0025, 0.004, 0.0055]}
# (scene, integrator, h or tol): status, stop time, message
FAILURES = {
    ("valley-sideways", "euler", HS[0]): ("diverged", 1.3, "non-finite state at t = 1.3"),
    ("valley-sideways", "exp-euler", HS[0]): ("lift-off", 0.8, "normal force F.N = -0.02 <= 0 at t = 0.8"),
    ("valley-sideways", "gsl-rkf45-adaptive", 1e-12): ("step-underflow", 0.4, "gsl: step size underflow | h < 1e-15"),
}
# (scene, integrator): (verdict per component, ci95) planted in the orders; the rest are "as declared"
PLANTED_VERDICTS = {
    ("plane", "rkmk8"): ("inconclusive", 0.6),
    ("valley-sideways", "gsl-rk4"): ("lower", 0.05),
}
COMPONENT_SCALE = {"contact": 1.0, "centre": 1.1, "omega": 3.0}
# the report's "error_components" as rollbench writes them (bench/lib/error_components.hpp)
ERROR_COMPONENTS = [
    {"name": "contact", "label": "contact-point error", "unit": "m", "scale": "radius"},
    {"name": "centre", "label": "centre error", "unit": "m", "scale": "radius"},
    {"name": "omega", "label": "angular-velocity error", "unit": "rad/s", "scale": "omega_scale"},
    {"name": "rotation", "label": "rotation error", "unit": "rad", "scale": "1"},
]
COMPONENTS = tuple(c["name"] for c in ERROR_COMPONENTS)
# ball radius and omega scale are 1, so "worst" is the largest component


def fixed_law(scene, name, component="contact"):
    """(C, p): the component's error is C * h^p; for "worst", the component that dominates over HS."""
    _, p, prot, c, crot, _, _ = FIXED[name]
    c, crot = c * SCENE_FACTOR[scene], crot * SCENE_FACTOR[scene]
    if component == "worst":
        laws = [fixed_law(scene, name, k) for k in COMPONENTS]
        top = [max(laws, key=lambda law: law[0] * h ** law[1]) for h in HS]
        assert all(t == top[0] for t in top), f"no single component dominates for {name}"
        return top[0]
    return (crot, prot) if component == "rotation" else (COMPONENT_SCALE[component] * c, p)


def fixed_error(scene, name, h, component="contact"):
    c, p = fixed_law(scene, name, component)
    return c * h ** p


def fixed_rhs(name, h):
    return FIXED[name][5] * T_END / h


def fixed_wall(name, h):
    return fixed_rhs(name, h) * FIXED[name][6] * 1e-9


def adaptive_law(scene, name, component="contact"):
    """(A, s): the component's error is A * tol^s."""
    _, _, a, _, _, _, s, rot = ADAPTIVE[name]
    a *= SCENE_FACTOR[scene]
    if component == "worst":
        return max(adaptive_law(scene, name, k) for k in COMPONENTS)
    return (a * (rot if component == "rotation" else COMPONENT_SCALE[component]), s)


def adaptive_error(scene, name, tol, component="contact"):
    a, s = adaptive_law(scene, name, component)
    return a * tol ** s


def adaptive_rhs(name, tol):
    _, _, _, k, q, _, _, _ = ADAPTIVE[name]
    return k * tol ** (-1.0 / q)


def adaptive_wall(name, tol):
    return adaptive_rhs(name, tol) * ADAPTIVE[name][5] * 1e-9


def _wall(median):
    samples = [median * s for s in SAMPLE_SPREAD]
    return {"median": float(np.median(samples)), "min": min(samples), "max": max(samples),
            "repeats": len(samples), "samples": samples}


def _errors(scene, value_of):
    floor = SCENES[scene][1]
    error = {"reference": SCENES[scene][0], "floor": floor, "below_floor": []}
    for c in COMPONENTS + ("worst",):
        v = value_of(c)
        if v < floor:
            error[c] = None
            error["below_floor"].append(c)
        else:
            error[c] = v
    return error


def _run(scene, name, family, order, rotation_order, adaptive, setting, error, rhs, wall, steps):
    status, stop, message = FAILURES.get((scene, name, setting), ("ok", T_END, ""))
    failed = status != "ok"
    run = {"scene": scene, "integrator": name, "family": family, "declared_order": order,
           "declared_rotation_order": rotation_order, "adaptive": adaptive,
           "tableau": TABLEAU.get(name), "on_group": family == "rkmk",
           "h": None if adaptive else setting, "rtol": setting if adaptive else None,
           "atol": setting if adaptive else None, "status": status, "message": message,
           "stop_time": stop, "steps": steps, "rejected": 3 if adaptive else 0, "rhs_evals": rhs,
           "jacobian_evals": 0, "exp_evals": steps if family == "rkmk" else 0,
           "dexpinv_evals": 4 * steps if family == "rkmk" else 0, "wall_s": _wall(wall),
           "error": _errors(scene, error), "error_max": _errors(scene, lambda c: ERROR_MAX_FACTOR * error(c)),
           "drift": {"energy": 1e-3 * math.sqrt(error("contact")), "rotation_defect":
                     1e-15 if family == "rkmk" else error("rotation")},
           "final": {"t": stop, "contact": [0.0, 0.0]}}
    if failed:
        for key in ("error", "error_max"):
            for c in COMPONENTS + ("worst",):
                run[key][c] = None
            run[key]["below_floor"] = []
    return run


def _orders(runs, floors):
    out = []
    for scene in SCENES:
        for name, (family, p, prot, *_rest) in FIXED.items():
            group = [r for r in runs if r["scene"] == scene and r["integrator"] == name and r["status"] == "ok"]
            verdict, ci = PLANTED_VERDICTS.get((scene, name), ("as declared", 0.01))
            observed, fits = {}, {}
            for c in COMPONENTS:
                pts = [(r["h"], r["error"][c]) for r in group
                       if r["error"][c] is not None and r["error"][c] > 10 * floors[scene]]
                h, e = np.log([x[0] for x in pts]), np.log([x[1] for x in pts])
                observed[c] = float(np.polyfit(h, e, 1)[0])
                if verdict == "lower":
                    observed[c] -= 1.0
                fits[c] = {"h_min": min(x[0] for x in pts), "h_max": max(x[0] for x in pts),
                           "points": len(pts), "r2": 1.0}
            out.append({"scene": scene, "integrator": name, "declared": p, "declared_rotation": prot,
                        "observed": observed, "ci95": {c: ci for c in COMPONENTS},
                        "verdict": {c: verdict for c in COMPONENTS}, "fit": fits["contact"], "fits": fits})
    return out


def _tolerance_fits():
    """The fits the runner would report: exact on the synthetic power laws (log10 worst against log10 tol)."""
    out = []
    for scene in SCENES:
        for name in ADAPTIVE:
            a, s = adaptive_law(scene, name, "worst")
            out.append({"scene": scene, "integrator": name, "slope": s, "intercept": math.log10(a),
                        "residual": 0.0, "points": len(TOLS)})
    return out


# largest stable step of the stability study, and the rotation defect there
STABLE_H = {"euler": 2 ** -6, "exp-euler": 2 ** -5, "rk4": 2 ** -2, "rkmk4": 2 ** -1,
            "rkmk4-seminar": 2 ** -2, "odeint-rk4": 2 ** -2, "gsl-rk4": 2 ** -3}
ROTATION_DEFECT = {"euler": 0.3, "exp-euler": 4e-16, "rk4": 2e-3, "rkmk4": 6e-16,
                   "rkmk4-seminar": 5e-16, "odeint-rk4": 2.5e-3, "gsl-rk4": 1e-4}
ENERGY_ERROR = {"euler": 0.4, "exp-euler": 0.3, "rk4": 2e-6, "rkmk4": 1e-6, "rkmk4-seminar": 3e-6,
                "odeint-rk4": 2e-6, "gsl-rk4": 5e-7}
# how the first unstable rung fails (bench/lib/stability_verdict.hpp's names)
STABILITY_FAILURE = {"euler": "rotation-defect", "exp-euler": "energy", "rk4": "rotation-defect",
                     "rkmk4": "stopped", "rkmk4-seminar": "energy-growth", "odeint-rk4": "rotation-defect",
                     "gsl-rk4": "energy"}
STABILITY_BOUNDS = {"energy": 1.0, "rotation_defect": 0.5, "growth_exponent": 3.0, "growth_floor": 1e-9}
STABILITY_HS = [2.0 ** -k for k in range(8, -1, -1)]


def _stability():
    t = np.logspace(-2, 3, 30)
    # energy error, rotation defect, stop time (None: reaches the end)
    growth = {
        "euler": (1e-3 * t ** 2, 1e-4 * t ** 2, 300.0),
        "exp-euler": (1e-3 * t, 2e-16 * (1 + 0.3 * np.sin(t)), None),
        "rk4": (4e-9 * t, 1e-10 * t, None),
        "rkmk4": (1e-9 * t, 1e-15 * (1 + 0.3 * np.cos(t)), None),
    }
    drift = []
    for name, (energy, defect, stop) in growth.items():
        keep = t <= (stop or t[-1])
        drift.append({"scene": "valley-sideways", "integrator": name, "family": FIXED[name][0], "h": 0.01,
                      "status": "diverged" if stop else "ok",
                      "message": f"non-finite state at t = {stop}" if stop else "",
                      "stop_time": stop or float(t[-1]), "t": t[keep].tolist(),
                      "energy_error": energy[keep].tolist(), "rotation_defect": defect[keep].tolist(),
                      "steps": int((stop or t[-1]) / 0.01), "rhs_evals": int(FIXED[name][5] * (stop or t[-1]) / 0.01),
                      "wall_s": 0.5})
    stable = []
    for scene in SCENES:
        for name, h in STABLE_H.items():
            if scene == "valley-sideways" and name == "euler":
                h = None  # no tested step passes
            tried = [{"h": x, "status": "ok", "stable": True, "failure": None}
                     for x in STABILITY_HS if h is not None and x <= h]
            # the first unstable rung: each way of failing on some method
            first = {"h": 2 * h if h else min(STABILITY_HS), "status": "ok", "stable": False,
                     "energy_error": 1.5, "rotation_defect": 0.7,
                     "growth": {"energy_error": {"p_early": 2.0, "p_late": 4.0, "exponential": True},
                                "rotation_defect": {"p_early": 1.0, "p_late": 1.0, "exponential": False}},
                     "failure": STABILITY_FAILURE[name]}
            if first["failure"] == "stopped":
                first["status"] = "chart-limit"
            stable.append({"scene": scene, "integrator": name, "family": FIXED[name][0], "h": h,
                           "horizon": 10.0, "tried": tried + [first],
                           "rotation_defect": None if h is None else ROTATION_DEFECT[name],
                           "energy_error": None if h is None else ENERGY_ERROR[name],
                           "thresholds": STABILITY_BOUNDS})
    return {"drift": drift, "largest_stable_h": stable}


def make_report():
    runs = []
    for scene in SCENES:
        for name, (family, p, prot, *_rest) in FIXED.items():
            for h in HS:
                runs.append(_run(scene, name, family, p, prot, False, h, lambda c: fixed_error(scene, name, h, c),
                                 fixed_rhs(name, h), fixed_wall(name, h), int(round(T_END / h))))
        for name, (family, p, *_rest) in ADAPTIVE.items():
            for tol in TOLS:
                rhs = adaptive_rhs(name, tol)
                runs.append(_run(scene, name, family, p, p, True, tol, lambda c: adaptive_error(scene, name, tol, c),
                                 rhs, adaptive_wall(name, tol), int(rhs / 6)))
    floors = {s: f for s, (_, f) in SCENES.items()}
    report = {
        "schema": "rollbench.report/2", "created": "2026-11-22T12:00:00Z", "git": "synthetic",
        "machine": {"cpu": "Synthetic CPU", "cores": 2, "os": "Linux", "load": [0.1, 0.1, 0.1]},
        "build": {"compiler": "g++ 12.2", "flags": "-O3", "type": "Release", "libraries": {}},
        "preset": "custom",
        "error_components": copy.deepcopy(ERROR_COMPONENTS),
        "references": [{"scene": s, "kind": k, "method": "exact" if k == "exact" else "rk8pd h/2 cross-check",
                        "cross_check": "—" if k == "exact" else "dopri5 tol 1e-14", "error": f,
                        "inertia": INERTIA.get(s), "r_feeds_back": s in INERTIA}
                       for s, (k, f) in SCENES.items()],
        "runs": runs,
        "orders": None,
        "stability": _stability(),
        "tolerance_fits": _tolerance_fits(),
    }
    report["orders"] = _orders(runs, floors)
    return report


def minimal_report():
    """Runs only: no orders, references, stability, tolerance fits (a quick preset's report)."""
    report = make_report()
    for key in ("orders", "references", "stability", "tolerance_fits"):
        del report[key]
    return report


def subset(report, scene, integrators):
    """A copy with one scene's runs of some integrators (a small report for quick tests)."""
    out = copy.deepcopy(report)
    out["runs"] = [r for r in out["runs"] if r["scene"] == scene and r["integrator"] in integrators]
    return out


def slowed(report, factor, integrator=None):
    """A copy with every raw timing sample (of one integrator, or all) multiplied by factor."""
    out = copy.deepcopy(report)
    for r in out["runs"]:
        if integrator is None or r["integrator"] == integrator:
            w = r["wall_s"]
            w["samples"] = [s * factor for s in w["samples"]]
            w["median"], w["min"], w["max"] = (float(np.median(w["samples"])), min(w["samples"]),
                                               max(w["samples"]))
    return out


def perf_json():
    """A Google Benchmark --benchmark_out file for the fixed-step methods."""
    benchmarks = []
    for scene in ("valley-sideways", "bowl-3d"):
        for name, (_, _, _, _, _, stages, ns) in FIXED.items():
            per_step = stages * ns * (1.2 if scene == "bowl-3d" else 1.0)
            benchmarks.append({"name": f"steps/{scene}/{name}", "run_name": f"steps/{scene}/{name}",
                               "run_type": "iteration", "iterations": 1000, "real_time": per_step,
                               "cpu_time": per_step, "time_unit": "us", "ns_per_step": per_step,
                               "rhs_per_step": float(stages)})
    return {"context": {"date": "2026-11-22", "num_cpus": 2}, "benchmarks": benchmarks}


def trajectory_csv(path):
    """A trajectory CSV (docs/formats.md column order) that swings across the valley while falling down it."""
    cols = ["t", "x", "y", "cx", "cy", "cz", "wx", "wy", "wz", "r00", "r01", "r02", "r10", "r11", "r12",
            "r20", "r21", "r22", "energy", "normal_force", "spin", "rotation_defect"]
    t = np.linspace(0.0, T_END, 201)
    x = 0.25 * np.cos(2.5 * t)
    y = 0.4 * t ** 2
    rows = np.zeros((t.size, len(cols)))
    rows[:, 0], rows[:, 1], rows[:, 2] = t, x, y
    with open(path, "w", encoding="utf-8") as f:
        f.write(",".join(cols) + "\n")
        for row in rows:
            f.write(",".join(f"{v:.17g}" for v in row) + "\n")


# ball-deforms.png: R = (I + g t e1 e1^T) Rz(t), so the ball's axes ratio at time t is exactly 1 + g t
BALL_GROWTH = {"euler": 0.2, "rk4": 0.02, "rkmk4": 0.0}


def ball_csv(path, growth):
    """A trajectory CSV whose R is a rotation stretched along x by 1 + growth * t."""
    cols = ["t", "x", "y", "cx", "cy", "cz", "wx", "wy", "wz", "r00", "r01", "r02", "r10", "r11", "r12",
            "r20", "r21", "r22", "energy", "normal_force", "spin", "rotation_defect"]
    t = np.linspace(0.0, T_END, 41)
    with open(path, "w", encoding="utf-8") as f:
        f.write(",".join(cols) + "\n")
        for tk in t:
            c, s = math.cos(tk), math.sin(tk)
            r = np.diag([1 + growth * tk, 1.0, 1.0]) @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
            row = [tk] + [0.0] * 8 + list(r.ravel()) + [0.0] * 4
            f.write(",".join(f"{v:.17g}" for v in row) + "\n")

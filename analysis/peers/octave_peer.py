"""GNU Octave's ode45, ode23 and ode15s as peers of rollbench's methods (docs/peers.md).

The seminar the suite grew from was a MATLAB program; these are its users'
default solvers. Octave calls the scene's flat right-hand side from
librollbench_problem.so through an oct-file (analysis/peers/octave/rb_problem.cc,
built here with mkoctfile), ode15s with the exact Jacobian, over a ladder of
tolerances (RelTol = AbsTol = tol), and this script writes a peer file
(docs/formats.md, "Peer runs") with one trajectory CSV per solve, for
`rollbench score --peers`.

Timing: tic/toc around each solve with its output times, the interpreter's
overhead included; rhs_evals come from the library's own counter, and the bare
cost of one rhs and one Jacobian call through the oct-file is measured apart
(rhs_cost), since every call crosses the interpreter.

    /usr/bin/python3 -m analysis.peers.octave_peer --scene chaplygin-valley --t-end 2 --out out/peers/octave
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from analysis.peers import peer_file, problem_lib

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "octave")
# name: (report name, declared order, the order as Octave's documentation states it, uses the Jacobian)
METHODS = {
    "ode45": ("octave-ode45", 5, "5(4) Dormand–Prince", False),
    "ode23": ("octave-ode23", 3, "3(2) Bogacki–Shampine", False),
    "ode15s": ("octave-ode15s", 5, "variable 1–5 (SUNDIALS IDA, BDF)", True),
}
DEFAULT_TOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
TIMING = ("wall_s: tic/toc around each solve with its output times, per timed repeat, Octave's interpreter "
          "included (every rhs call crosses it into the oct-file); rhs_cost: the bare rhs and Jacobian through the "
          "same oct-file, timed apart, so that rhs_evals x interpreter_s_per_call is the evaluations' share")


class OctaveError(Exception):
    """Octave or mkoctfile missing, or a run of Octave that failed."""


def tool(name):
    path = shutil.which(name)
    if not path:
        raise OctaveError(f"'{name}' not found: install Debian's octave and liboctave-dev "
                          "(scripts/install-deps.sh --tests)")
    return path


def build_oct_file(folder):
    """rb_problem.oct from rb_problem.cc into folder."""
    include = os.path.join(problem_lib.ROOT, "problems", "abi")
    out = os.path.join(folder, "rb_problem.oct")
    done = subprocess.run([tool("mkoctfile"), f"-I{include}", "-o", out, os.path.join(HERE, "rb_problem.cc"), "-ldl"],
                          capture_output=True, text=True, cwd=folder)
    if done.returncode != 0:
        raise OctaveError(f"mkoctfile failed: {done.stderr.strip()}")
    return out


def octave_version():
    done = subprocess.run([tool("octave-cli"), "--version"], capture_output=True, text=True)
    return done.stdout.splitlines()[0] if done.returncode == 0 and done.stdout else "unknown"


def solve_scene(library, scene, t_end, dt_out, methods, tols, repeats, rhs_calls, oct_dir, work):
    """Octave on one scene: its result (the JSON solve_peers.m writes)."""
    with problem_lib.Problem(problem_lib.load_library(library), scene, t_end) as problem:
        times = peer_file.output_times(dt_out or peer_file.ERROR_DT, problem.t_end)
    spec = {"library": os.path.abspath(library), "scene": scene, "t_end": float(t_end), "times": times.tolist(),
            "methods": methods, "tols": list(tols), "repeats": repeats, "rhs_calls": rhs_calls, "out_dir": work,
            "result_file": os.path.join(work, "result.json")}
    spec_file = os.path.join(work, "spec.json")
    with open(spec_file, "w") as out:
        json.dump(spec, out)
    command = f"addpath('{oct_dir}'); addpath('{HERE}'); solve_peers('{spec_file}');"
    done = subprocess.run([tool("octave-cli"), "--no-gui", "--norc", "--no-window-system", "--eval", command],
                          capture_output=True, text=True)
    if not os.path.exists(spec["result_file"]):
        raise OctaveError(f"octave failed on scene '{scene}' (exit {done.returncode}): {done.stderr.strip()[-800:]}")
    with open(spec["result_file"]) as f:
        result = json.load(f)
    os.remove(spec["result_file"])
    return result, times


def steps_of(run):
    """(steps, where the count comes from). Octave returns no step count with output times, so a second solve
    without them counts its steps: the timed solve's where both made the same evaluations (ode45, ode23); IDA
    (ode15s) stops at each output time, so there it is another solve's, said so."""
    steps, untimed, timed = int(run["steps"]), int(run["untimed_rhs_evals"]), int(run["rhs_evals"])
    if steps >= 0 and untimed == timed:
        return steps, "timed solve"
    if steps >= 0:
        return steps, f"a solve without output times ({untimed} rhs evaluations, the timed solve {timed})"
    return int(run["outputs"]), "lower bound: one step per output time (the solve without output times failed)"


def peer_run(problem, run, times, work, folder, stem):
    """One Octave solve as a peer-file run, its trajectory written."""
    name, order, order_text, uses_jacobian = METHODS[run["method"]]
    raw = np.fromfile(os.path.join(work, run["states"]), dtype=np.float64)
    outputs = raw.reshape(-1, problem_lib.STATE_SIZE).T[:, :int(run["outputs"])]
    rows, checks, status, message, stop_time = peer_file.checked_trajectory(
        problem, times, outputs, run["status"], run["message"], float(run["t_reached"]))
    path = peer_file.write_trajectory(problem, folder, stem, rows)
    steps, source = steps_of(run)
    return {"integrator": name, "family": "octave", "method": run["method"], "declared_order": order,
            "declared_order_text": order_text, "needs_jacobian": uses_jacobian, "rtol": run["tol"],
            "atol": run["tol"], "status": status, "message": message, "stop_time": stop_time, "trajectory": path,
            "wall_s": [float(w) for w in np.atleast_1d(run["wall_s"])], "steps": steps,
            "rhs_evals": int(run["rhs_evals"]), "jacobian_evals": int(run["jacobian_evals"]),
            "lu_decompositions": None, "validity_checks": checks,
            "options": {"stages_beyond_model": int(run["beyond"]), "steps_source": source}}


def run_peers(library, scenes, methods, tols, t_end, dt_out, repeats, rhs_calls, folder, progress=print):
    os.makedirs(folder, exist_ok=True)
    lib = problem_lib.load_library(library)
    runs, costs = [], []
    with tempfile.TemporaryDirectory() as work:
        oct_dir = os.path.dirname(build_oct_file(work))
        for scene in scenes:
            result, times = solve_scene(library, scene, t_end, dt_out, methods, tols, repeats, rhs_calls, oct_dir,
                                        work)
            cost = dict(result["rhs_cost"], scene=scene)
            costs.append(cost)
            with problem_lib.Problem(lib, scene, t_end) as problem:
                for run in result["runs"]:
                    stem = f"{problem.name}-{METHODS[run['method']][0]}-{run['tol']:.0e}"
                    entry = peer_run(problem, run, times, work, folder, stem)
                    entry["scene"] = scene
                    runs.append(entry)
                    progress(f"octave_peer: {problem.name} {run['method']} tol {run['tol']:.0e}: {entry['status']}, "
                             f"{entry['rhs_evals']} rhs, {np.median(entry['wall_s']) * 1e3:.1f} ms")
    versions = {"octave": octave_version()}
    return peer_file.write_peer_file(folder, "octave", versions, library, problem_lib.ABI_VERSION, t_end, dt_out,
                                     TIMING, costs, runs)


def main(argv=None):
    return peer_file.main(argv, __doc__, "octave_peer", METHODS, "Octave's", DEFAULT_TOLS, 2000, run_peers,
                          (problem_lib.ProblemError, OctaveError))


if __name__ == "__main__":
    sys.exit(main())

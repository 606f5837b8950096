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

from analysis import safe_files
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


def private_env():
    """The environment of mkoctfile and Octave: the caller's, with the temporary folder the working folder (a
    private one, `cwd`): mkoctfile pastes $TMPDIR into the shell commands it runs, so no text of the caller's
    may stand there."""
    return dict(os.environ, TMPDIR=".", TMP=".", TEMP=".")


def build_oct_file(folder):
    """rb_problem.oct from rb_problem.cc, built in folder (private: this process made it); its path.

    The source and its header are copied in and mkoctfile is given only their bare names, run in folder:
    mkoctfile runs the compiler through a shell command line, so no path of the caller's is in it."""
    shutil.copyfile(os.path.join(HERE, "rb_problem.cc"), os.path.join(folder, "rb_problem.cc"))
    shutil.copyfile(os.path.join(problem_lib.ROOT, "problems", "abi", "rollbench_problem.h"),
                    os.path.join(folder, "rollbench_problem.h"))
    done = subprocess.run([tool("mkoctfile"), "-o", "rb_problem.oct", "rb_problem.cc", "-ldl"],
                          capture_output=True, text=True, errors="backslashreplace", cwd=folder, env=private_env())
    if done.returncode != 0:
        raise OctaveError(f"mkoctfile failed: {done.stderr.strip()}")
    return os.path.join(folder, "rb_problem.oct")


def octave_command(code):
    """octave-cli's argument vector for code: no startup file (--norc: neither ~/.octaverc, ./.octaverc nor the
    site's), this package's folder first on the path; run with cwd a private folder, so that nothing in the caller's
    working folder (a planted solve_peers.m) is found first."""
    return [tool("octave-cli"), "--no-gui", "--norc", "--no-history", "--no-window-system", "--path", HERE,
            "--eval", code]


def octave_version(work):
    done = subprocess.run([tool("octave-cli"), "--norc", "--version"], capture_output=True, text=True,
                          errors="backslashreplace", cwd=work, env=private_env())
    return done.stdout.splitlines()[0] if done.returncode == 0 and done.stdout else "unknown"


def solve_scene(library, scene, t_end, dt_out, methods, tols, repeats, rhs_calls, work):
    """Octave on one scene: its result (the JSON solve_peers.m writes). work: the private folder that holds
    rb_problem.oct, Octave's working folder; the spec names its files relative to it."""
    with problem_lib.Problem(problem_lib.load_library(library), scene, t_end) as problem:
        times = peer_file.output_times(dt_out or peer_file.ERROR_DT, problem.t_end)
    # a scene file's path made absolute, as Octave runs elsewhere (a path: with '/' or ending in .json, as
    # rb::load_scene tells them; a shipped scene's name as is)
    is_path = "/" in scene or (len(scene) > 5 and scene.endswith(".json"))
    spec = {"library": os.path.abspath(library), "scene": os.path.abspath(scene) if is_path else scene,
            "t_end": float(t_end), "times": times.tolist(), "methods": methods, "tols": list(tols),
            "repeats": repeats, "rhs_calls": rhs_calls, "out_dir": ".", "result_file": "result.json"}
    safe_files.write_file(os.path.join(work, "spec.json"), json.dumps(spec))
    done = subprocess.run(octave_command("solve_peers('spec.json');"), capture_output=True, text=True,
                          errors="backslashreplace", cwd=work, env=private_env())
    result_file = os.path.join(work, spec["result_file"])
    if not os.path.exists(result_file):
        raise OctaveError(f"octave failed on scene {safe_files.shown(scene)} (exit {done.returncode}): "
                          f"{done.stderr.strip()[-800:]}")
    result = json.loads(safe_files.read_text(result_file, "peer result", safe_files.PEER_FILE_LIMIT))
    os.remove(result_file)
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
    raw = np.frombuffer(safe_files.read_bytes(os.path.join(work, run["states"]), "peer result",
                                              safe_files.TRAJECTORY_LIMIT), dtype=np.float64)
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
    with safe_files.output_folder(folder) as out:
        return _run_peers(library, scenes, methods, tols, t_end, dt_out, repeats, rhs_calls, out, progress)


def _run_peers(library, scenes, methods, tols, t_end, dt_out, repeats, rhs_calls, folder, progress):
    lib = problem_lib.load_library(library)
    runs, costs = [], []
    # private (0700, made here): mkoctfile and Octave run in it, and it holds their every file
    with tempfile.TemporaryDirectory() as work:
        build_oct_file(work)
        versions = {"octave": octave_version(work)}
        for scene in scenes:
            result, times = solve_scene(library, scene, t_end, dt_out, methods, tols, repeats, rhs_calls, work)
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
    return peer_file.write_peer_file(folder, "octave", versions, library, problem_lib.ABI_VERSION, t_end, dt_out,
                                     TIMING, costs, runs)


def main(argv=None):
    return peer_file.main(argv, __doc__, "octave_peer", METHODS, "Octave's", DEFAULT_TOLS, 2000, run_peers,
                          (problem_lib.ProblemError, OctaveError, safe_files.InputFileError))


if __name__ == "__main__":
    sys.exit(main())

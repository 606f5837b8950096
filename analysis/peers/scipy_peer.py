"""SciPy's solve_ivp as a peer of rollbench's methods (docs/peers.md).

Runs RK45, DOP853, Radau, BDF and LSODA (the implicit ones with the exact
Jacobian) on the scene's flat right-hand side from librollbench_problem.so,
over a ladder of tolerances (rtol = atol = tol, as rollbench's adaptive
runs), and writes a peer file (docs/formats.md, "Peer runs") with one
trajectory CSV per solve, for `rollbench score --peers` to turn into report
runs.

Timing: each solve is timed with time.perf_counter around solve_ivp and the
evaluation of its dense output at the output times, Python's overhead
included; the cost of the bare right-hand side and Jacobian through ctypes is
measured apart (rhs_cost) so that readers can subtract it.

    /usr/bin/python3 -m analysis.peers.scipy_peer --scene chaplygin-valley --t-end 2 --out out/peers
"""
import platform
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

from analysis import safe_files
from analysis.peers import peer_file, problem_lib

# name: (report name, declared order, the order as SciPy's documentation states it, uses the Jacobian)
METHODS = {
    "RK45": ("scipy-rk45", 5, "5(4)", False),      # Dormand–Prince, steps with the order-5 solution
    "DOP853": ("scipy-dop853", 8, "8(5,3)", False),  # Dormand–Prince 8, 5th- and 3rd-order estimates
    "Radau": ("scipy-radau", 5, "5", True),          # Radau IIA, 3 stages
    "BDF": ("scipy-bdf", 5, "variable 1–5", True),   # NDF/BDF; the declared order is the highest
    "LSODA": ("scipy-lsoda", 12, "variable: Adams 1–12, BDF 1–5", True),  # switched by stiffness
}
DEFAULT_TOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
TIMING = ("wall_s: time.perf_counter around solve_ivp (dense_output=True) and the evaluation of its dense "
          "output at the output times, per timed repeat, Python's overhead included (the right-hand side is "
          "called through ctypes); rhs_cost: the bare rhs and Jacobian through the same ctypes wrapper at the "
          "start, timed apart, so that rhs_evals x python_s_per_call is the evaluations' share to subtract")
STATUS_OF_CODE = {"diverged", "lift-off", "curvature", "domain"}


def measure_rhs_cost(problem, calls):
    """Seconds per call: the bare ctypes call, the wrapper solve_ivp calls, and the Jacobian's wrapper."""
    y = problem.y0.copy()
    dy = np.empty(problem_lib.STATE_SIZE)
    problem.rhs(0.0, y), problem.jacobian(0.0, y)  # warm: first calls pay for lazy binding
    f, h, yp, dyp = problem._rhs, problem.handle, y.ctypes.data, dy.ctypes.data
    start = time.perf_counter()
    for _ in range(calls):
        f(h, 0.0, yp, dyp)
    bare = (time.perf_counter() - start) / calls
    start = time.perf_counter()
    for _ in range(calls):
        problem.rhs(0.0, y)
    wrapped = (time.perf_counter() - start) / calls
    jac_calls = max(1, calls // 10)
    start = time.perf_counter()
    for _ in range(jac_calls):
        problem.jacobian(0.0, y)
    jac = (time.perf_counter() - start) / jac_calls
    problem.reset()
    return {"scene": None, "calls": calls, "ctypes_s_per_call": bare, "python_s_per_call": wrapped,
            "jacobian_calls": jac_calls, "jacobian_s_per_call": jac}


def solve(problem, method, tol, times):
    """One solve to the last output time: (solution at the outputs or None, solve_ivp's result)."""
    jac = {"jac": problem.jacobian} if METHODS[method][3] else {}  # the explicit methods warn on any jac
    sol = solve_ivp(problem.rhs, (0.0, times[-1]), problem.y0, method=method, rtol=tol, atol=tol,
                    dense_output=True, **jac)
    reached = times[times <= sol.t[-1] * (1 + 1e-14)]
    outputs = sol.sol(reached) if sol.sol is not None and len(reached) else np.empty((problem_lib.STATE_SIZE, 0))
    return outputs, sol


def failure_of(sol):
    """(status, message) of a solve that did not get to the end."""
    if sol.success:
        return "ok", ""
    status = "step-underflow" if "step size" in sol.message.lower() else "error"
    return status, f"solve_ivp: {sol.message} (t = {sol.t[-1]:.6g})"


def run_one(problem, method, tol, times, repeats, folder, stem):
    """Solves once for the counts and the trajectory, then `repeats` more times for the timing."""
    name, order, order_text, uses_jacobian = METHODS[method]
    problem.reset()
    outputs, sol = solve(problem, method, tol, times)
    rhs_evals, jacobian_evals = problem.counts()
    stages_beyond = problem.stages_beyond
    status, message = failure_of(sol)
    rows, checks, status, message, stop_time = peer_file.checked_trajectory(
        problem, times, outputs, status, message, float(sol.t[-1]))
    wall = []
    for _ in range(repeats):
        start = time.perf_counter()
        solve(problem, method, tol, times)
        wall.append(time.perf_counter() - start)
    problem.reset()
    path = peer_file.write_trajectory(problem, folder, stem, rows)
    return {"integrator": name, "family": "scipy", "method": method, "declared_order": order,
            "declared_order_text": order_text, "needs_jacobian": uses_jacobian, "rtol": tol, "atol": tol,
            "status": status, "message": message, "stop_time": stop_time, "trajectory": path,
            "wall_s": wall, "steps": len(sol.t) - 1, "rhs_evals": rhs_evals, "jacobian_evals": jacobian_evals,
            "lu_decompositions": int(sol.nlu), "validity_checks": checks,
            "options": {"stages_beyond_model": stages_beyond, "nfev": int(sol.nfev), "njev": int(sol.njev)}}


def run_peers(library, scenes, methods, tols, t_end, dt_out, repeats, rhs_calls, folder, progress=print):
    # the output folder opened first, under the path rule (analysis/safe_files.py); every file goes through it
    with safe_files.output_folder(folder) as out:
        return _run_peers(library, scenes, methods, tols, t_end, dt_out, repeats, rhs_calls, out, progress)


def _run_peers(library, scenes, methods, tols, t_end, dt_out, repeats, rhs_calls, folder, progress):
    lib = problem_lib.load_library(library)
    runs, costs, ends = [], [], set()
    for scene in scenes:
        with problem_lib.Problem(lib, scene, t_end or 0.0) as problem:
            ends.add(problem.t_end)
            times = peer_file.output_times(dt_out or peer_file.ERROR_DT, problem.t_end)
            cost = measure_rhs_cost(problem, rhs_calls)
            cost["scene"] = scene
            costs.append(cost)
            for method in methods:
                for tol in tols:
                    stem = f"{problem.name}-{METHODS[method][0]}-{tol:.0e}"
                    run = run_one(problem, method, tol, times, repeats, folder, stem)
                    run["scene"] = scene
                    runs.append(run)
                    progress(f"scipy_peer: {problem.name} {method} tol {tol:.0e}: {run['status']}, "
                             f"{run['rhs_evals']} rhs, {np.median(run['wall_s']) * 1e3:.1f} ms")
    versions = {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__}
    path = peer_file.write_peer_file(folder, "scipy", versions, library, problem_lib.ABI_VERSION, t_end, dt_out, TIMING,
                                     costs, runs)
    return path


def main(argv=None):
    return peer_file.main(argv, __doc__, "scipy_peer", METHODS, "solve_ivp's", DEFAULT_TOLS, 20000, run_peers,
                          problem_lib.ProblemError)


if __name__ == "__main__":
    sys.exit(main())

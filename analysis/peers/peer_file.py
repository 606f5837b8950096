"""What every peer writes the same way (docs/formats.md, "Peer runs"): the
runner's output grid, one trajectory CSV per solve with each output state
through the model's checks, and peers.json."""
import json
import math
import os

import numpy as np

from analysis import safe_files

ERROR_DT = 0.25  # the runner's error grid (rollbench run without --dt-out)
SCHEMA = "rollbench.peers/1"


def output_times(spacing, t_end):
    """The runner's output grid: k spacing (k = 1, 2, ...) below t_end, then t_end (bench/lib/trajectory_csv.cpp)."""
    count = math.floor(t_end / spacing * (1.0 - 1e-12))
    times = [k * spacing for k in range(1, count + 1)]
    if not times or times[-1] < t_end:
        times.append(t_end)
    return np.array(times)


def csv_header(problem):
    c, d = problem.components, problem.derived_names
    return ",".join(["t"] + c[12:14] + d[0:6] + c[0:9] + d[6:10])


def csv_row(problem, t, y):
    d = problem.derived(y)
    values = [t, y[12], y[13], *d[0:6], *y[0:9], *d[6:10]]
    return ",".join("%.17g" % v for v in values)


def checked_trajectory(problem, times, outputs, status, message, stop_time):
    """The CSV rows of the output states (a 14 x n array, n <= len(times)), each through the model's checks as
    the suite checks each accepted state; the first beyond the model ends the run there.
    Returns (rows, validity checks, status, message, stop_time)."""
    rows, checks = [], 1
    for k in range(outputs.shape[1]):
        checks += 1
        verdict, reason = problem.check(outputs[:, k])
        if verdict != "ok":
            return rows, checks, verdict, f"{reason} (output t = {times[k]:.6g})", float(times[k])
        rows.append(csv_row(problem, float(times[k]), outputs[:, k]))
    return rows, checks, status, message, stop_time


def write_trajectory(problem, folder, stem, rows):
    """trajectories/STEM.csv under folder (a path or a safe_files.OutputFolder), starting at the start state; the
    path relative to folder."""
    text = "".join(r + "\n" for r in [csv_header(problem), csv_row(problem, 0.0, problem.y0), *rows])
    with safe_files.output_folder(folder) as out, out.subfolder("trajectories") as trajectories:
        trajectories.write_text(f"{stem}.csv", text)
    return os.path.join("trajectories", f"{stem}.csv")


def write_peer_file(folder, peer, versions, library, abi_version, t_end, dt_out, timing, rhs_cost, runs):
    """folder/peers.json (folder: a path or a safe_files.OutputFolder); its path."""
    peers = {"schema": SCHEMA, "peer": peer, "versions": versions, "library": os.path.abspath(library),
             "abi_version": abi_version, "t_end": t_end if t_end else None, "dt_out": dt_out if dt_out else None,
             "timing": timing, "rhs_cost": rhs_cost, "runs": runs}
    with safe_files.output_folder(folder) as out:
        return out.write_text("peers.json", json.dumps(peers, indent=1))


def main(argv, doc, peer, methods, owner, default_tols, rhs_calls, run_peers, errors):
    """A peer's command line (its module's main): parse and check the arguments, run the peer, exit status.

    methods: the peer's solvers by name; owner: whose they are, for an unknown one ("solve_ivp's", "Octave's");
    errors: the exceptions that are bad input (exit 2 with the message)."""
    import argparse
    import sys
    from analysis.peers import problem_lib

    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("--library", default=problem_lib.DEFAULT_LIBRARY, help="librollbench_problem.so")
    ap.add_argument("--scene", action="append", required=True, help="a shipped scene or a scene file (repeatable)")
    ap.add_argument("--methods", default=",".join(methods), help="comma-separated solver names")
    ap.add_argument("--tol", default=",".join(f"{t:g}" for t in default_tols), help="comma-separated tolerances")
    ap.add_argument("--t-end", type=float, default=0.0, help="end time, as rollbench run --t-end (0: the scene's)")
    ap.add_argument("--dt-out", type=float, default=0.0, help="output spacing, as rollbench run --dt-out "
                                                              "(0: the runner's error grid, 0.25)")
    ap.add_argument("--repeats", type=int, default=3, help="timed solves per run")
    ap.add_argument("--rhs-calls", type=int, default=rhs_calls, help="bare rhs calls timed for rhs_cost")
    ap.add_argument("--out", required=True, help="folder for peers.json and trajectories/")
    a = ap.parse_args(argv)
    chosen = a.methods.split(",")
    unknown = [m for m in chosen if m not in methods]
    if unknown:
        ap.error(f"unknown method {unknown[0]!r}; {owner} are {', '.join(methods)}")
    try:
        tols = [float(t) for t in a.tol.split(",")]
    except ValueError:
        ap.error(f"--tol: expected comma-separated numbers, got {a.tol!r}")
    if not all(t > 0 for t in tols) or a.repeats < 1 or a.rhs_calls < 1 or a.t_end < 0 or a.dt_out < 0:
        ap.error("tolerances, --repeats and --rhs-calls must be > 0, --t-end and --dt-out >= 0")
    # the peer file holds the scenes and the library as JSON text: a path that is not UTF-8 cannot be written there
    for option, path in [("--library", a.library)] + [("--scene", s) for s in a.scene]:
        try:
            path.encode("utf-8")
        except UnicodeEncodeError:
            print(f"{peer}: {option} {safe_files.shown(path)} is not UTF-8; the peer file records it as JSON text, "
                  "so name it by a UTF-8 path", file=sys.stderr)
            return 2
    try:
        path = run_peers(a.library, a.scene, chosen, tols, a.t_end, a.dt_out, a.repeats, a.rhs_calls, a.out,
                         progress=lambda line: print(line, file=sys.stderr))
    except (errors if isinstance(errors, tuple) else (errors,)) + (safe_files.OutputFileError,) as e:
        print(f"{peer}: {e}", file=sys.stderr)
        return 2
    print(f"peer file written to {safe_files.shown(path)}")
    return 0

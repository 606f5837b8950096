"""What every peer writes the same way (docs/formats.md, "Peer runs"): the
runner's output grid, one trajectory CSV per solve with each output state
through the model's checks, and peers.json."""
import json
import math
import os

import numpy as np

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
    """trajectories/STEM.csv under folder, starting at the start state; the path relative to folder."""
    path = os.path.join("trajectories", f"{stem}.csv")
    os.makedirs(os.path.join(folder, "trajectories"), exist_ok=True)
    with open(os.path.join(folder, path), "w") as out:
        out.write(csv_header(problem) + "\n" + csv_row(problem, 0.0, problem.y0) + "\n")
        out.writelines(r + "\n" for r in rows)
    return path


def write_peer_file(folder, peer, versions, library, abi_version, t_end, dt_out, timing, rhs_cost, runs):
    """folder/peers.json; its path."""
    peers = {"schema": SCHEMA, "peer": peer, "versions": versions, "library": os.path.abspath(library),
             "abi_version": abi_version, "t_end": t_end if t_end else None, "dt_out": dt_out if dt_out else None,
             "timing": timing, "rhs_cost": rhs_cost, "runs": runs}
    path = os.path.join(folder, "peers.json")
    with open(path, "w") as out:
        json.dump(peers, out, indent=1)
    return path

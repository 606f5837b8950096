#!/usr/bin/env bash
# The peers beside rollbench's own methods in one report, with its figures
# (docs/peers.md): a rollbench sweep, SciPy's five solve_ivp methods and GNU
# Octave's ode45, ode23 and ode15s on the same scenes and end time,
# `rollbench score --peers --into` joining each, and the analysis' plots.
#
#   scripts/peers.sh [OUT]        (default OUT: out/peers)
#
# RB_PEERS (default "scipy,octave"; Octave needs Debian's octave and
# liboctave-dev, which `scripts/install-deps.sh --tests` installs),
# RB_PEER_SCENES (default "valley-sideways,chaplygin-valley": a homogeneous
# ball, and one whose orientation feeds back), RB_PEER_TOLS (1e-3,...,1e-10),
# RB_PEER_INTEGRATORS (rollbench's methods). The end time is the quick
# preset's, t = 2 (`run` has no --t-end; the peer is given the same).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/peers}
scenes=${RB_PEER_SCENES:-valley-sideways,chaplygin-valley}
t_end=2  # the quick preset's
tols=${RB_PEER_TOLS:-1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10}
integrators=${RB_PEER_INTEGRATORS:-rk4,rkmk4,cf4,odeint-rk4,rkmk-dp54-adaptive,rkmk-dp853-adaptive,odeint-dopri5-adaptive,gsl-rk8pd-adaptive,gsl-msbdf-adaptive}
build=$root/build/release
python=/usr/bin/python3

cd "$root"
cmake --preset release >/dev/null
cmake --build --preset release --target rollbench rollbench_problem
mkdir -p "$out"
"$build/rollbench" run --preset quick --scenes "$scenes" --integrators "$integrators" --h '2^-2..2^-9' --tol "$tols" \
  --no-stability --cache "$out/cache" --out "$out/rollbench.json"
scene_args=()
IFS=, read -ra scene_list <<< "$scenes"
for s in "${scene_list[@]}"; do scene_args+=(--scene "$s"); done
report=$out/rollbench.json
IFS=, read -ra peer_list <<< "${RB_PEERS:-scipy,octave}"
for peer in "${peer_list[@]}"; do
  case "$peer" in scipy|octave) ;; *) echo "peers.sh: unknown peer '$peer' in RB_PEERS (scipy, octave)" >&2; exit 2 ;; esac
  "$python" -m "analysis.peers.${peer}_peer" --library "$build/librollbench_problem.so" "${scene_args[@]}" \
    --t-end "$t_end" --tol "$tols" --out "$out/$peer"
  "$build/rollbench" score --peers "$out/$peer/peers.json" --into "$report" --cache "$out/cache" \
    --out "$out/with-$peer.json"
  report=$out/with-$peer.json
done
cp "$report" "$out/report.json"
RB_ROLLBENCH="$build/rollbench" "$python" analysis/plot.py "$out/report.json" --out "$out/plots"
echo "report: $out/report.json, figures and summary.md: $out/plots"

#!/usr/bin/env bash
# The measured tables of README.md and docs/: runs the sweeps and writes
# docs/results/*.md (command, date, commit, machine and wall time in each)
# and the README's headline block (from the default preset: every scene where R feeds back),
# so that no measured number is typed by hand. Run from a built tree
# (scripts/build.sh); the reports and plots land in OUT (default out/results).
#   default.md   rollbench run --preset default: every method on every scene
#   headline.md  the Lie-group methods against the best general-purpose ones,
#                on homogeneous scenes and where R feeds back (5 repeats)
#   exp-products.md  commutator-free and Crouch-Grossman against RKMK and the
#                libraries (5 repeats)
#   regime.md    rollbench run --preset regime: the regime map over its default
#                grid of generated scenes (docs/usage.md, "The regime study")
# Names as arguments run only those: scripts/results.sh headline
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/results}"
bin=./build/release
mkdir -p "$out" docs/results

wanted() { [ ${#only[@]} -eq 0 ] || [[ " ${only[*]} " == *" $1 "* ]]; }
only=("$@")

sweep() {  # name title command...
  local name=$1 title=$2
  shift 2
  wanted "$name" || return 0
  local start end readme=()
  # the default preset (every scene where R feeds back) also writes the README's headline
  [ "$name" != default ] || readme=(--readme README.md)
  start=$(date +%s)
  "$@" --out "$out/$name.json" > "$out/$name.txt"
  end=$(date +%s)
  /usr/bin/python3 analysis/results.py "$out/$name.json" --out "docs/results/$name.md" --title "$title" \
    --command "$*" --wall-s $((end - start)) "${readme[@]}"
}

sweep default "Results: the default preset" \
  "$bin/rollbench" run --preset default --cache .cache/references

sweep headline "Results: Lie-group methods against the best general-purpose ones" \
  "$bin/rollbench" run --scenes bumpy-long,valley-rest,valley-sideways,chaplygin-valley,chaplygin-bumpy-long \
  --integrators rk-dp54-adaptive,rkmk-dp54-adaptive,rkmk-dp853-adaptive,rk-f78-adaptive,rkmk-f78-adaptive,odeint-fehlberg78-adaptive,odeint-dopri5-adaptive,gsl-rk8pd-adaptive,rk4-projected,rk4-quaternion,rkmk4,rkmk5,rkmk8,rk4,odeint-fehlberg78 \
  --tol 1e-1,3e-2,1e-2,3e-3,1e-3,3e-4,1e-4,3e-5,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12 \
  --h 2^0..2^-10 --repeats 5 --jobs 2 --cache .cache/references

sweep exp-products "Results: exponentials only (commutator-free, Crouch-Grossman) against RKMK and the libraries" \
  "$bin/rollbench" run --scenes valley-sideways,chaplygin-valley,bumpy-long \
  --integrators cf4,cg3,cg4a,cf4-reversed,cg3-reversed,cg4a-reversed,rkmk4,rkmk4-cayley,rkmk5,rk4,odeint-rk4,odeint-dopri5-adaptive,odeint-fehlberg78-adaptive,gsl-rk8pd-adaptive,rkmk-dp54-adaptive \
  --h 2^0..2^-10 --tol 1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11 --repeats 5 --jobs 2 --cache .cache/references

sweep regime "Results: the regime map" \
  "$bin/rollbench" run --preset regime --cache .cache/references

if wanted default; then /usr/bin/python3 analysis/plot.py "$out/default.json" --out "$out/plots"; fi
if wanted regime; then /usr/bin/python3 analysis/plot.py "$out/regime.json" --out "$out/regime-plots"; fi
echo "pages in docs/results/; plots of the default preset: $out/plots/, of the regime map: $out/regime-plots/"

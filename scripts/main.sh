#!/usr/bin/env bash
# The main job: build, then integrate the default scene with rkmk4 and rk4 and
# print a summary of each run (the sweep runner and plots replace this when
# they land). Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
mkdir -p out
for method in rkmk4 rk4; do
  ./build/release/rollbench trajectory valley-sideways --integrator "$method" --h 0.01 \
    --out "out/valley-sideways-$method.csv"
done
echo "trajectories written to $(pwd)/out/"

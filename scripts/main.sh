#!/usr/bin/env bash
# The main job: build, run the default benchmark preset (every registered
# integrator on every shipped scene, plus the stability study), time the
# fixed-step methods per step with Google Benchmark, and make the plots.
# Everything lands in out/ (override with OUT=dir). Installs what it needs
# first (apt, only when something is missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out}"
./scripts/install-deps.sh
./scripts/build.sh
mkdir -p "$out/trajectories"
bin=./build/release

"$bin/rollbench" run --preset default --cache .cache/references --out "$out/report.json"

"$bin/perf_steps" --benchmark_min_time=0.05 --benchmark_out="$out/perf.json" \
  --benchmark_out_format=json > "$out/perf.txt"

# the contact point's path on every shipped scene, for the landscape plots
for scene_file in problems/scenes/*.json; do
  scene=$(basename "$scene_file" .json)
  "$bin/rollbench" trajectory "$scene" --integrator rkmk4 --h 0.001953125 --dt-out 0.015625 \
    --out "$out/trajectories/$scene.csv" > /dev/null
done

/usr/bin/python3 analysis/plot.py "$out/report.json" --perf "$out/perf.json" \
  --trajectories "$out/trajectories" --out "$out/plots"

echo
echo "report:     $(pwd)/$out/report.json"
echo "timings:    $(pwd)/$out/perf.txt"
echo "plots:      $(pwd)/$out/plots/  (summary: $out/plots/summary.md)"

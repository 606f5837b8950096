#!/usr/bin/env bash
# The main job: build, run the default benchmark preset (every registered
# integrator on every shipped scene, plus the stability and horizon studies), time the
# fixed-step methods per step with Google Benchmark, and make the plots.
# Everything lands in out/ (override with OUT=dir). Installs what it needs
# first (apt, only when something is missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out}"
./scripts/install-deps.sh
./scripts/build.sh rollbench perf_steps
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

# "the ball deforms": 20 s on gaussian-hills, each method at a step where a
# flat method's R visibly leaves SO(3) (axes ratio about 1.5 at the end)
mkdir -p "$out/ball-gaussian-hills"
for run in euler:0.001 rk4:0.08 rkmk4:0.08; do
  "$bin/rollbench" trajectory gaussian-hills --integrator "${run%%:*}" --h "${run#*:}" --dt-out 0.4 --t-end 20 \
    --out "$out/ball-gaussian-hills/${run%%:*}-h${run#*:}.csv" > /dev/null
done

/usr/bin/python3 analysis/plot.py "$out/report.json" --perf "$out/perf.json" \
  --trajectories "$out/trajectories" --ball "$out/ball-gaussian-hills" --out "$out/plots"

echo
echo "report:     $(pwd)/$out/report.json"
echo "timings:    $(pwd)/$out/perf.txt"
echo "plots:      $(pwd)/$out/plots/  (summary: $out/plots/summary.md)"

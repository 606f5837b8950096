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

# the per-run table (hundreds of lines) goes to a file; the findings are printed at the end
"$bin/rollbench" run --preset default --cache .cache/references --out "$out/report.json" > "$out/run.txt"

# no colour codes in a file; Google Benchmark's "Library was built as DEBUG"
# warning is about the Debian libbenchmark package itself, not rollbench's
# own code (built with -O2): the timed steps are ours, so it is said once here
echo "perf_steps: Google Benchmark may warn that its library was built as DEBUG: that is the system" \
  "package's own build; the timed code (rollbench's steps) is this Release build"
"$bin/perf_steps" --benchmark_min_time=0.05 --benchmark_color=false --benchmark_out="$out/perf.json" \
  --benchmark_out_format=json > "$out/perf.txt" 2> "$out/perf.stderr.txt"

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
# the answer first: the findings of summary.md (up to its next section)
sed -n '/^## Findings/,/^### /p' "$out/plots/summary.md" | sed '$d'
echo
# where the outputs are, absolute whether OUT was given relative (to the project's root) or absolute
case "$out" in
  /*) where="$out" ;;
  *) where="$(pwd)/$out" ;;
esac
echo "per-run table: $where/run.txt (\"best worst\": the smallest worst error a method reached;"
echo "  \"its time\": the wall time of that run; adaptive methods have no order)"
echo "report:     $where/report.json"
echo "timings:    $where/perf.txt"
echo "plots:      $where/plots/  (summary: $where/plots/summary.md)"

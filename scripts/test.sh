#!/usr/bin/env bash
# Every test: installs the dependencies, builds, prints the per-step timing
# table in its short mode (no timing is asserted), then runs the GoogleTest
# suite and the analysis tests through CTest. The README's test command; CI
# runs it too.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
for perf in build/release/perf_*; do
  echo "== $perf (short mode)"
  "$perf" --benchmark_min_time=0.01
done
ctest --preset release -j 2 --timeout 900

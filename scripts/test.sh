#!/usr/bin/env bash
# Every test: installs the dependencies (the tests' own too), builds, prints
# the per-step timing table in its short mode (no timing is asserted), runs
# through CTest the GoogleTest suite, the analysis tests, the docs' link check
# and the SLURM test (a single-node cluster on localhost), then the robustness
# script: each libFuzzer target for 60 s and the test suite again under
# ASan + UBSan (a clang build in build/robustness). The README's test
# command; CI runs it.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh --tests
./scripts/build.sh
for perf in build/release/perf_*; do
  echo "== $perf (short mode)"
  "$perf" --benchmark_min_time=0.01
done
ctest --preset release -j 2 --timeout 900
./scripts/robustness.sh

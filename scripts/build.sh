#!/usr/bin/env bash
# Configures and builds the release preset (build/release), on every core of
# the machine (CMAKE_BUILD_PARALLEL_LEVEL overrides).
#   scripts/build.sh                 everything: the tools, the benchmarks, the tests
#   scripts/build.sh TARGET ...      only those targets (the main job needs no test binary)
set -euo pipefail
cd "$(dirname "$0")/.."
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}"
cmake --preset release >/dev/null
if [ $# -eq 0 ]; then
  cmake --build --preset release
else
  cmake --build --preset release --target "$@"
fi

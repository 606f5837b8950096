#!/usr/bin/env bash
# Every test: installs the dependencies, builds, runs the GoogleTest suite
# through CTest. The README's test command; CI runs it too.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
ctest --preset release -j 2 --timeout 900

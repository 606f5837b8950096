#!/usr/bin/env bash
# Installs what rollbench needs from Debian's packages (run as root, or with
# sudo available). Checks with dpkg-query first and runs apt only for what is
# missing, so it is quick when everything is there.
#   scripts/install-deps.sh           what the build and the main job need
#   scripts/install-deps.sh --tests   that and what only the tests need
set -euo pipefail
packages=(
  g++ cmake ninja-build make
  libeigen3-dev nlohmann-json3-dev libboost-dev libgsl-dev libcli11-dev
  libgtest-dev libbenchmark-dev
  # HMAC-SHA256 for the native-formula cache (problems/native_cache.cpp)
  libssl-dev
  python3 python3-matplotlib python3-numpy python3-scipy libbenchmark-tools
  # scripts/robustness.sh: libFuzzer and the sanitizer runtimes, llvm-symbolizer for stacks
  clang-14 libclang-rt-14-dev llvm-14
)
# only scripts/test.sh needs these: the SLURM test's single-node cluster
# (tests/slurm/test_slurm.sh), chromium for the index.html test, flake8 for
# the Python lint (lint.python), clang-format for the C++ one (lint.format);
# the main job stays lean without them; octave and liboctave-dev for the Octave
# peer's test (tests/peers/test_octave_peer.py: mkoctfile builds its oct-file)
test_packages=(slurm-wlm munge chromium python3-flake8 clang-format-14 octave liboctave-dev)
case "${1:-}" in
  "") ;;
  --tests) packages+=("${test_packages[@]}") ;;
  *) echo "usage: $0 [--tests]" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
# wait for another apt on the same machine rather than fail
apt=(apt-get -o DPkg::Lock::Timeout=600)
$sudo "${apt[@]}" update -qq
DEBIAN_FRONTEND=noninteractive $sudo "${apt[@]}" install -y -qq "${missing[@]}"

#!/usr/bin/env bash
# Installs everything rollbench needs from Debian's packages (run as root, or
# with sudo available). Safe to run again: apt skips what is installed.
set -euo pipefail
packages=(
  g++ cmake ninja-build make
  libeigen3-dev nlohmann-json3-dev libboost-dev libgsl-dev libcli11-dev
  libgtest-dev libbenchmark-dev
  python3 python3-matplotlib python3-numpy python3-scipy chromium libbenchmark-tools
  # scripts/robustness.sh: libFuzzer and the sanitizer runtimes, llvm-symbolizer for stacks
  clang-14 libclang-rt-14-dev llvm-14
)
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
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"

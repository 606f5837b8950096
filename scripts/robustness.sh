#!/usr/bin/env bash
# Robustness (docs/bad-input.md): scenes and formulas are text from
# anyone, and the methods measured fail in every way. One clang-14 build with
# AddressSanitizer and UndefinedBehaviorSanitizer (RB_SANITIZE=ON, RB_FUZZ=ON;
# clang builds it several times faster than g++ and its UBSan also checks
# float-to-integer casts), then
#   1. the libFuzzer targets in fuzz/ run for FUZZ_SECONDS each (default 60),
#      from the seed corpora in fuzz/corpus/ plus what earlier runs found
#      (kept in the build folder); any crash, leak, timeout, out-of-memory or
#      sanitizer report fails;
#   2. the whole test suite runs under the sanitizers with ctest.
# Usage: scripts/robustness.sh [fuzz|tests] [--fuzz-seconds N] [--fuzz-seed S]   (default: both, 60 s, seed 1)
# Environment: FUZZ_SECONDS (60), FUZZ_SEED (1; the options win), BUILD_DIR (build/robustness), JOBS (2).
# The seed fixes libFuzzer's choices, so that a finding of CI's run is found
# again by the same command (docs/fuzzing.md); --fuzz-seed 0 lets libFuzzer
# pick one (printed in the log), for runs that should explore anew.
# CI keeps 60 s a target. The long mode (docs/fuzzing.md) is the same run with
# hours a target, e.g. `scripts/robustness.sh fuzz --fuzz-seconds 14400`; the
# corpus grown in $BUILD_DIR/corpus carries over from run to run.
# A g++ sanitizer build works too: cmake -B build/asan -DRB_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
usage() { echo "usage: $0 [fuzz|tests] [--fuzz-seconds N] [--fuzz-seed S]" >&2; exit 2; }
parts=all
fuzz_seconds="${FUZZ_SECONDS:-60}"
fuzz_seed="${FUZZ_SEED:-1}"
while [ $# -gt 0 ]; do
  case "$1" in
    all | fuzz | tests) parts="$1" ;;
    --fuzz-seconds) [ $# -ge 2 ] || usage; fuzz_seconds="$2"; shift ;;
    --fuzz-seconds=*) fuzz_seconds="${1#*=}" ;;
    --fuzz-seed) [ $# -ge 2 ] || usage; fuzz_seed="$2"; shift ;;
    --fuzz-seed=*) fuzz_seed="${1#*=}" ;;
    *) usage ;;
  esac
  shift
done
case "$fuzz_seconds" in '' | *[!0-9]* | 0) echo "$0: --fuzz-seconds wants a whole number of seconds > 0, got '$fuzz_seconds'" >&2; exit 2 ;; esac
case "$fuzz_seed" in '' | *[!0-9]*) echo "$0: --fuzz-seed wants a whole number >= 0 (0: libFuzzer picks), got '$fuzz_seed'" >&2; exit 2 ;; esac
build="${BUILD_DIR:-build/robustness}"
jobs="${JOBS:-2}"
targets=(fuzz_formula fuzz_scene fuzz_run)
declare -A dict=([fuzz_formula]=fuzz/formula.dict [fuzz_scene]=fuzz/scene.dict [fuzz_run]=fuzz/scene.dict)
start=$SECONDS

./scripts/install-deps.sh

# a UB report or a leak is an error, with a symbolised stack
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
symbolizer="$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)"
[ -z "$symbolizer" ] || export ASAN_SYMBOLIZER_PATH="$symbolizer"

echo "== robustness: building with clang-14, ASan + UBSan, in $build"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRB_SANITIZE=ON -DRB_FUZZ=ON -DRB_BUILD_TESTS=ON -DRB_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$jobs"
echo "== robustness: built in $((SECONDS - start)) s"

# a fuzzer's failure is printed again at the very end: CI shows only the
# last lines, which the sanitizer ctest run would otherwise fill
fuzz_failures=""
run_fuzzers() {
  local failed=0 summary="" t
  for t in "${targets[@]}"; do
    local corpus="$build/corpus/$t" artifacts="$build/artifacts/$t/" log="$build/$t.log" rc=0
    # artifacts are this run's findings only (copy one elsewhere to keep it)
    rm -rf "$artifacts"
    mkdir -p "$corpus" "$artifacts"
    echo "== robustness: $t for ${fuzz_seconds} s, seed $fuzz_seed"
    # new inputs go to the first folder; the seeds in fuzz/corpus stay as they are
    "$build/fuzz/$t" "$corpus" "fuzz/corpus/$t" -dict="${dict[$t]}" -max_total_time="$fuzz_seconds" -seed="$fuzz_seed" \
      -timeout=10 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 -artifact_prefix="$artifacts" \
      >"$log" 2>&1 || rc=$?
    local execs rate found
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
    found=$(find "$artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
    if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ] || grep -q "runtime error:" "$log"; then
      failed=1
      local report
      report="!! $t FAILED (exit $rc, $found inputs saved in $artifacts); the end of $log:"$'\n'"$(tail -n 60 "$log")"
      echo "$report"
      fuzz_failures+="$report"$'\n'
    fi
    summary+=$(printf '  %-13s %10s runs %7s runs/s  corpus %5s  exit %s' "$t" "${execs:-?}" "${rate:-?}" \
      "$(find "$corpus" -type f | wc -l)" "$rc")$'\n'
  done
  echo "== robustness: fuzzing, ${fuzz_seconds} s a target, seed $fuzz_seed"
  printf '%s' "$summary"
  return "$failed"
}

status=0
if [ "$parts" != tests ]; then run_fuzzers || status=1; fi
if [ "$parts" != fuzz ]; then
  echo "== robustness: the test suite under ASan + UBSan"
  ctest --test-dir "$build" -j "$jobs" --output-on-failure --timeout 900 || status=1
fi
[ -z "$fuzz_failures" ] || printf '== robustness: the fuzzers failed (as above):\n%s' "$fuzz_failures"
echo "== robustness: $([ "$status" -eq 0 ] && echo passed || echo FAILED) in $((SECONDS - start)) s"
exit "$status"

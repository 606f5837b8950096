#!/usr/bin/env bash
# The C and C++ sources follow .clang-format: lists every file clang-format
# would change (and how, with --diff) and exits 1 if there is one.
#   scripts/check-format.sh          check (CTest's lint.format)
#   scripts/check-format.sh --fix    rewrite the files in place
set -euo pipefail
cd "$(dirname "$0")/.."
format="$(command -v clang-format-14 || command -v clang-format || true)"
[ -n "$format" ] || { echo "check-format: clang-format-14 is not installed (scripts/install-deps.sh --tests)" >&2; exit 2; }
mapfile -t files < <(find bench integrators problems tests fuzz examples \
  -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.c' -o -name '*.h' \) | sort)
if [ "${1:-}" = --fix ]; then
  "$format" -i "${files[@]}"
  exit 0
fi
bad=0
for f in "${files[@]}"; do
  if ! "$format" --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "check-format: $f is not formatted as .clang-format says (scripts/check-format.sh --fix); the change:"
    "$format" "$f" | diff -u "$f" - | head -20 || true
    bad=1
  fi
done
[ "$bad" -eq 0 ] && echo "check-format: ${#files[@]} files formatted as .clang-format says"
exit "$bad"

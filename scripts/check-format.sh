#!/usr/bin/env bash
# Fails, naming the files, when a C++ source is not as .clang-format says (clang-format 14,
# Debian 12's). Fix with: scripts/check-format.sh --fix
# Usage: scripts/check-format.sh [--fix]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
command -v clang-format >/dev/null ||
    { echo "check-format: clang-format is missing (apt-get install clang-format, or scripts/install-deps.sh --tests)" >&2; exit 1; }
mapfile -t files < <(find algo bench cli core formats nodes python/src tests util \
    -name '*.cc' -o -name '*.h' | sort)
if [ "${1:-}" = "--fix" ]; then
    clang-format -i "${files[@]}"
    exit 0
fi
bad=()
for f in "${files[@]}"; do
    clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
    echo "check-format: ${#bad[@]} file(s) not formatted (scripts/check-format.sh --fix):" >&2
    printf '  %s\n' "${bad[@]}" >&2
    exit 1
fi
echo "check-format: ${#files[@]} files formatted"

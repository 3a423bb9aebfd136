#!/usr/bin/env bash
# Rewrites the golden graphs' expected statistics (tests/golden/expected/*.json) after an
# intended change in behaviour, then shows what moved; review it and commit it with the change
# (docs/testing.md, "Golden graphs").
# Usage: scripts/update-golden.sh [BUILD_DIR] [gtest flags, e.g. --gtest_filter='*figure6*']
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
shift || true

"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" > /dev/null
cmake --build "$build" -j "$(nproc)" --target cloudgraph_golden_tests
CLOUDGRAPH_GOLDEN_UPDATE=1 "$build/tests/golden/cloudgraph_golden_tests" "$@"
git -C "$root" diff --stat -- tests/golden/expected

#!/usr/bin/env bash
# Configures and builds CloudGraph.  Usage: scripts/build.sh [BUILD_DIR] [extra cmake args...]
# CLOUDGRAPH_TARGETS (space-separated) builds only those targets and what they need (the
# default run builds the CLI alone); unset or empty builds everything.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
shift || true
"$root/scripts/install-deps.sh"
# Paths under the checkout are hashed relative to it, so a second clone reuses ccache's objects.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" "$@" > /dev/null
targets=()
for t in ${CLOUDGRAPH_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" -j "$(nproc)" "${targets[@]}"

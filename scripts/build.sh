#!/usr/bin/env bash
# Configures and builds CloudGraph.  Usage: scripts/build.sh [BUILD_DIR] [extra cmake args...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
shift || true
"$root/scripts/install-deps.sh"
# Paths under the checkout are hashed relative to it, so a second clone reuses ccache's objects.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" "$@" > /dev/null
cmake --build "$build" -j "$(nproc)"

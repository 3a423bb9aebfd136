#!/usr/bin/env bash
# Installs what is missing, builds, and cooks the default scene end to end into out/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" "$root/build"
cd "$root"
./build/cli/cloudgraph run graphs/default.json --out out --cache out/cache --report out/report.json "$@"

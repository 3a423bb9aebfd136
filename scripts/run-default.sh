#!/usr/bin/env bash
# Installs what is missing, builds, and renders the default scene (the paper's Figure 6)
# end to end into out/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# The CLI and the libraries it links, not the tests and benchmarks: the first picture sooner.
CLOUDGRAPH_TARGETS=cloudgraph "$root/scripts/build.sh" "$root/build"
cd "$root"
./build/cli/cloudgraph run graphs/figure6_towering_cumulus.json --out out --cache out/cache \
    --report out/report.json "$@"

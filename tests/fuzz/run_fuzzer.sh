#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time on its seeds. New inputs go to a scratch
# directory, or to $CLOUDGRAPH_FUZZ_CORPUS when set (kept between runs); the seed directory in
# git is only read. A crashing input is written under FINDINGS_DIR.
# Usage: run_fuzzer.sh BINARY SEED_DIR SECONDS FINDINGS_DIR [libFuzzer flags...]
set -euo pipefail
binary=$1 seeds=$2 seconds=$3 findings=$4
shift 4
[ -n "$(ls -A "$seeds")" ] || { echo "run_fuzzer: no seeds in $seeds" >&2; exit 1; }
corpus=${CLOUDGRAPH_FUZZ_CORPUS:-}
if [ -z "$corpus" ]; then
    corpus=$(mktemp -d)
    trap 'rm -rf "$corpus"' EXIT
fi
mkdir -p "$corpus" "$findings"
# libFuzzer writes new inputs into the first directory only. -timeout makes a slow input a
# finding; -rss_limit_mb (and the malloc limit it implies) one that allocates without bound.
"$binary" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$@" "$corpus" "$seeds"

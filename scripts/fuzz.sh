#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, in build-fuzz/: the configuration of CI's
# second build, so after CI nothing rebuilds) and runs each longer than ctest's few seconds.
# Usage: scripts/fuzz.sh [TARGET|all] [SECONDS] [libFuzzer flags...]
#   TARGET   one of tests/fuzz/*.cc by name (graph_loader, http_request, serve_api, ...);
#            default all
#   SECONDS  per target; default 600
# New inputs accumulate in build-fuzz/fuzz-corpus/TARGET/, so a later run goes on from what
# earlier ones found; crashing inputs land in build-fuzz/fuzz-findings/TARGET/, the full output
# in build-fuzz/fuzz-logs/TARGET.log.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${CLOUDGRAPH_FUZZ_BUILD:-"$root/build-fuzz"}
which=${1:-all}
seconds=${2:-600}
shift $(($# < 2 ? $# : 2))

targets=()
for f in "$root"/tests/fuzz/*.cc; do
    t=$(basename "$f" .cc)
    [ "$which" = all ] || [ "$which" = "$t" ] && targets+=("$t")
done
[ ${#targets[@]} -gt 0 ] || { echo "fuzz: no target '$which' in tests/fuzz/" >&2; exit 2; }
"$root/scripts/install-deps.sh" --tests  # clang and the libFuzzer runtime
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DCLOUDGRAPH_WERROR=ON -DCLOUDGRAPH_SANITIZE=ON \
    -DCLOUDGRAPH_FUZZ=ON > /dev/null
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"

mkdir -p "$build/fuzz-logs"
status=0
for t in "${targets[@]}"; do
    log="$build/fuzz-logs/$t.log"
    echo "fuzz: $t for $seconds s (log: $log)"
    rc=0
    CLOUDGRAPH_FUZZ_CORPUS="$build/fuzz-corpus/$t" "$root/tests/fuzz/run_fuzzer.sh" \
        "$build/tests/fuzz/fuzz_$t" "$root/tests/fuzz/corpus/$t" "$seconds" \
        "$build/fuzz-findings/$t" "$@" > "$log" 2>&1 || rc=$?
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
    size=$(find "$build/fuzz-corpus/$t" -type f | wc -l)
    if [ "$rc" -eq 0 ]; then
        result="no finding"
    else
        status=1
        result="FINDING (exit $rc): $(sed -n 's/.*Test unit written to //p' "$log" | tail -n 1)"
    fi
    echo "fuzz: $t: ${runs:-?} executions, ${rate:-?} exec/s, corpus $size inputs: $result"
done
exit "$status"

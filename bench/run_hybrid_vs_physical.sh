#!/usr/bin/env bash
# The paper's headline claim, measured side by side in one run: the time of one step of the
# physical simulation (PrimitiveSim's SPH sub-step, sph_bench BM_SolverStep) against one frame
# of the hybrid method producing the same number of cloud particles (mapper_bench
# BM_HybridStep: condensation state, source selection, every position streamed), at 64k, 256k
# and 1M particles. Prints medians and the ratio.
# Usage: bench/run_hybrid_vs_physical.sh [BUILD_DIR] [REPETITIONS]   (a Release build)
set -euo pipefail
build=${1:-build}
reps=${2:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
common=(--benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true --benchmark_format=json)
"$build/bench/sph_bench" --benchmark_filter='BM_SolverStep/(64000|256000|1000000)' "${common[@]}" > "$tmp/sph.json"
"$build/bench/mapper_bench" --benchmark_filter='BM_HybridStep' "${common[@]}" > "$tmp/hybrid.json"
python3 - "$tmp" <<'PY'
import json, re, sys
tmp = sys.argv[1]
def medians(path, prefix):
    out = {}
    for b in json.load(open(f"{tmp}/{path}"))["benchmarks"]:
        if b.get("aggregate_name") != "median" or not b["run_name"].startswith(prefix):
            continue
        n = int(re.match(prefix + r"(\d+)", b["run_name"]).group(1))
        out[n] = b
    return out
sph = medians("sph.json", "BM_SolverStep/")
hyb = medians("hybrid.json", "BM_HybridStep/")
print(f"{'particles':>10s} {'SPH sub-step ms':>16s} {'hybrid frame ms':>16s} {'cloud particles':>16s} {'ratio':>8s}")
for n in sorted(hyb):
    s, h = sph.get(n) or sph[min(sph, key=lambda k: abs(k - n))], hyb[n]
    print(f"{n:>10,d} {s['real_time']:16.2f} {h['real_time']:16.3f} {h['particles']:16,.0f} {s['real_time'] / h['real_time']:8.0f}x")
PY

#!/usr/bin/env bash
# Runs the mapper benchmark (the library's forEachCloudChunk and generateCloudParticles) and
# prints medians, ratios to the write/copy peers, and the Figure 5 run's time and peak memory
# per final cloud particle.
# Usage: bench/run_mapper_bench.sh [BUILD_DIR] [FIGURE5_RUNS] [REPETITIONS]   (a Release build)
# Each Figure 5 run (streamed and materialised, FIGURE5_RUNS of each) is its own process, so
# that its ru_maxrss high-water mark is its own.
set -euo pipefail
build=${1:-build}
runs=${2:-5}
reps=${3:-7}
bin="$build/bench/mapper_bench"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$bin" --benchmark_filter='BM_(Generate|Fresh|Stream)' --benchmark_repetitions="$reps" \
    --benchmark_report_aggregates_only=true --benchmark_format=json > "$tmp/gen.json"
for i in $(seq "$runs"); do
    "$bin" --benchmark_filter='BM_Figure5/0' --benchmark_format=json > "$tmp/fig0_$i.json"
    "$bin" --benchmark_filter='BM_Figure5/1' --benchmark_format=json > "$tmp/fig1_$i.json"
done

python3 - "$tmp" "$runs" <<'PY'
import json, statistics, sys
tmp, runs = sys.argv[1], int(sys.argv[2])
gen = {b["run_name"]: b for b in json.load(open(f"{tmp}/gen.json"))["benchmarks"]
       if b.get("aggregate_name") == "median"}
def g(name): return gen[f"BM_{name}/real_time"]
n = g("GenerateStreamed")["particles"]
write, copy = g("StreamWrite")["bytes_per_second"], g("StreamCopy")["bytes_per_second"]
print(f"last frame: {n:,.0f} cloud particles; 12 bytes (xyz float32) counted per particle")
print(f"{'benchmark':24s} {'ms':>8s} {'M particles/s':>14s} {'GB/s':>7s} {'/write':>7s} {'/copy':>7s}")
for name in ["GenerateLibrary", "FreshFrameArrays", "GenerateFrameBuffer", "GenerateStreamed", "StreamWrite", "StreamCopy"]:
    b = g(name)
    bps = b["bytes_per_second"]
    print(f"{name:24s} {b['real_time']:8.2f} {b['items_per_second']/1e6:14.0f} {bps/1e9:7.2f} "
          f"{bps/write:7.2f} {bps/copy:7.2f}")

def fig(path):
    return [b for b in json.load(open(path))["benchmarks"] if b["run_type"] == "iteration"][0]
f0 = [fig(f"{tmp}/fig0_{i}.json") for i in range(1, runs + 1)]
f1 = [fig(f"{tmp}/fig1_{i}.json") for i in range(1, runs + 1)]
def show(label, bs):
    med = lambda k: statistics.median(b[k] for b in bs)
    print(f"{label}: {len(bs)} run(s), median total {med('real_time')/1e3:.2f} s "
          f"(selection {med('select_s'):.2f} s, generation {med('generate_s'):.2f} s), "
          f"{med('final_particles'):,.0f} final particles, {med('sources'):.0f} sources, "
          f"{med('particle_frames')/1e9:.3f} G particle-frames; peak memory beyond the inputs: "
          f"heap {med('heap_B_per_particle'):.3f} B, rss {med('rss_B_per_particle'):.3f} B per final particle")
    print("  totals (s): " + ", ".join(f"{b['real_time']/1e3:.2f}" for b in bs))
show("Figure 5, streamed (forEachCloudChunk)", f0)
show("Figure 5, generateCloudParticles", f1)
PY

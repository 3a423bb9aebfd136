#!/usr/bin/env bash
# Renders one 640 x 480 frame of a 5-million-particle cumulus voxelized by our Voxelizer
# (bench/render_bench.cc writes the .vdb) with our Renderer and with OpenVDB's vdb_render
# (package libopenvdb-tools) on the same .vdb, same resolution, same primary step (1 voxel),
# same camera and sun, in one run; and the reference path tracer on the same cloud at one path
# a pixel, scaled to the 2048 paths at which docs/rendering.md's error table calls it
# converged. Prints the medians and the ratios.
# Usage: bench/run_render_bench.sh [BUILD_DIR] [REPETITIONS]   (a Release build)
set -euo pipefail
build=${1:-build}
reps=${2:-5}
command -v vdb_render >/dev/null || { echo "vdb_render not found: apt-get install -y libopenvdb-tools" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

CG_RENDER_BENCH_VDB="$work/cumulus.vdb" "$build/bench/render_bench"
"$build/bench/render_bench" --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
    --benchmark_format=json > "$work/ours.json"

# vdb_render: camera at the still's position looking at the same point; its -fov is horizontal
# (aperture width), ours 40 degrees vertical at 4:3, i.e. 51.8 degrees horizontal. sigma_t =
# 0.05 /m as ours (scatter 0.0495 + absorb 0.0005, albedo 0.99); -light gets all six numbers:
# the direction toward the sun and its colour. -cpus 0: all cores, as ours.
vdb_args=(-res 640x480 -translate 400,-3800,700 -lookat 0,0,1200 -up 0,0,1 -fov 51.8
          -step 1 -shadowstep 3 -scatter 0.0495,0.0495,0.0495 -absorb 0.0005,0.0005,0.0005
          -light -1,-0.25,0.65,1,1,1 -cpus 0)
times=()
for ((i = 0; i < reps; ++i)); do
    start=$(date +%s.%N)
    vdb_render "$work/cumulus.vdb" "$work/vdb_render.png" "${vdb_args[@]}"
    end=$(date +%s.%N)
    times+=("$(echo "$end - $start" | bc)")
done
printf '%s\n' "${times[@]}" > "$work/vdb.txt"

python3 - "$work/ours.json" "$work/vdb.txt" <<'PY'
import json, statistics, sys
runs = {b["run_name"]: b for b in json.load(open(sys.argv[1]))["benchmarks"]
        if b.get("aggregate_name") == "median"}
vdb = statistics.median(float(t) for t in open(sys.argv[2]).read().split())
print(f"vdb_render (step 1, shadow step 3): {vdb * 1000:.0f} ms (median, whole process incl. file read)")
fast = next((b["real_time"] for name, b in runs.items()
             if "Render" in name and name.endswith("/50")), None)
for name, b in sorted(runs.items()):
    ms = b["real_time"]
    if "PathTrace" in name:
        converged = ms * 2048 / b["paths"]
        print(f"{name}: {ms:.0f} ms at {b['paths']:.0f} path(s) a pixel; "
              f"at 2048 paths {converged / 1000:.0f} s = {converged / 1000 / vdb:.0f} x vdb_render"
              + (f" = {converged / fast:.0f} x the fast mode at step 0.5" if fast else ""))
    elif "Render" in name:
        print(f"{name}: {ms:.0f} ms = {ms / 1000 / vdb:.2f} x vdb_render")
    else:
        print(f"{name}: {ms:.0f} ms")
PY

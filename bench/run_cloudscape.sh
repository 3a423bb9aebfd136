#!/usr/bin/env bash
# The 20 km cloudscape (graphs/cloudscape_20km.json): one late frame voxelized and rendered
# at 1280 x 720, its time and the process's peak memory.
#
#   bench/run_cloudscape.sh [BUILD_DIR] [REPETITIONS] [FRAME]     (defaults: build 3 487)
#
# The simulation states are cooked once into a cache (`run --simulations-only`, about 35 s:
# the primitive); each repetition then cooks the frame from a fresh copy of that cache, so
# the Voxelizer and the Renderer cook every time. Prints, per repetition, the cloud
# particles, the Voxelizer's and the Renderer's own seconds (from the run report) and the
# process's wall time and peak RSS (/usr/bin/time), then the medians.
set -euo pipefail

build=${1:-build}
reps=${2:-3}
frame=${3:-487}
graph=graphs/cloudscape_20km.json
cloudgraph=$build/cli/cloudgraph
work=$(mktemp -d /tmp/cloudscape_bench.XXXXXX)
trap 'rm -rf "$work"' EXIT

"$cloudgraph" run "$graph" --simulations-only --cache "$work/simulated" --out "$work/out" -q

for i in $(seq 1 "$reps"); do
    rm -rf "$work/cache" "$work/out"
    cp -a "$work/simulated" "$work/cache"
    # The video of this one frame keeps EncodeVideo's frame range inside the cooked frames.
    /usr/bin/time -f '%e %M' -o "$work/time.$i" "$cloudgraph" run "$graph" --frames "$frame:$frame" \
        --set "video.firstFrame=$frame" --set "video.lastFrame=$frame" --set counts.every=1 \
        --cache "$work/cache" --out "$work/out" --report "$work/report.$i.json" > "$work/log.$i" 2>&1
done

/usr/bin/python3 - "$work" "$reps" "$frame" <<'EOF'
import json, re, statistics, sys
work, reps, frame = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
total = re.search(r"total=(\d+)", open(f"{work}/log.1").read()).group(1)
print(f"cloud particles at frame {frame}: {int(total):,}")
rows = []
for i in range(1, reps + 1):
    nodes = json.load(open(f"{work}/report.{i}.json"))["nodes"]
    wall, rss_kb = open(f"{work}/time.{i}").read().split()
    rows.append((nodes["voxelize"]["seconds"], nodes["render"]["seconds"], float(wall), int(rss_kb) / 2**20))
print(f"frame {frame}, 1280 x 720; per repetition: voxelize s, render s, voxelize + render s, process wall s, peak RSS GiB")
for v, r, w, m in rows:
    print(f"  {v:6.2f} {r:6.2f} {v + r:6.2f} {w:7.2f} {m:6.2f}")
med = lambda k: statistics.median(k)
print(f"median: voxelize {med([r[0] for r in rows]):.2f} s, render {med([r[1] for r in rows]):.2f} s, "
      f"voxelize + render {med([r[0] + r[1] for r in rows]):.2f} s (goal <= 10), "
      f"peak RSS {med([r[3] for r in rows]):.2f} GiB (goal <= 4)")
EOF

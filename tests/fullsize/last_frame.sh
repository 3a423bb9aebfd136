#!/usr/bin/env bash
# Runs one shipped graph's last frame at full size, cold (its simulations step from the start),
# and checks that the run succeeds and writes that frame's image. The golden tests run small
# versions; this catches what only the full size reaches (a frame over a memory limit, as
# Figure 8 on its sounding did with 28 million particles).
# Usage: last_frame.sh CLI GRAPH WORK_DIR
set -euo pipefail
cli=$1 graph=$2 work=$3
name=$(basename "$graph" .json)
last=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['frames']['end'])" "$graph")
rm -rf "$work/$name" && mkdir -p "$work/$name"
trap 'rm -rf "$work/$name"' EXIT
start=$(date +%s)
# The video encoder encodes on its lastFrame from firstFrame on: start it at this frame.
set_video=()
if python3 -c "import json,sys; sys.exit(0 if 'video' in json.load(open(sys.argv[1]))['nodes'] else 1)" "$graph"; then
    set_video=(--set "video.firstFrame=$last")
fi
"$cli" run "$graph" --out "$work/$name/out" --cache "$work/$name/cache" --frames "$last:$last" -q \
    "${set_video[@]}"
echo "$name: frame $last in $(( $(date +%s) - start )) s"
# Every WriteImage node's file for that frame (#### is the frame number).
images=$(python3 -c "
import json, sys
nodes = json.load(open(sys.argv[1]))['nodes']
for n in nodes.values():
    if n['type'] == 'WriteImage':
        print(n['params']['file'].replace('####', '%04d' % int(sys.argv[2])))" "$graph" "$last")
for image in $images; do
    [ -s "$work/$name/out/$image" ] || { echo "$name wrote no $image" >&2; exit 1; }
done

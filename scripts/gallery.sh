#!/usr/bin/env bash
# Renders the gallery of docs/gallery.md: for every figure graph, four frames of its animation
# (one run per frame, sharing a disk cache, so the simulations step once) put side by side
# into docs/images/gallery_<graph>.png, and the last of them as the still
# docs/images/gallery_<graph>_still.png.
# Usage: scripts/gallery.sh [BUILD_DIR] [GRAPH ...]   (default: every graphs/figure*.json)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
shift || true
cli="$build/cli/cloudgraph"
command -v ffmpeg >/dev/null || { echo "gallery: ffmpeg is needed (scripts/install-deps.sh)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cache=${CLOUDGRAPH_GALLERY_CACHE:-"$work/cache"}

graphs=("$@")
[ ${#graphs[@]} -gt 0 ] || graphs=("$root"/graphs/figure*.json)
for graph in "${graphs[@]}"; do
    name=$(basename "$graph" .json)
    last=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['frames']['end'])" "$graph")
    frames=()
    for f in 0.25 0.45 0.7 1.0; do frames+=("$(python3 -c "print(round($last * $f))")"); done
    inputs=()
    for f in "${frames[@]}"; do
        # The video encoder encodes on its lastFrame from firstFrame on: start it at this frame.
        start=$(date +%s.%N)
        "$cli" run "$graph" --out "$work/$name" --cache "$cache" --frames "$f:$f" -q \
            --set "video.firstFrame=$f"
        echo "$name frame $f: $(echo "$(date +%s.%N) - $start" | bc) s"
        png=$(find "$work/$name" -name "frame.$(printf %04d "$f").png" | head -n 1)
        [ -n "$png" ] || { echo "gallery: $name wrote no frame.$(printf %04d "$f").png" >&2; exit 1; }
        inputs+=(-i "$png")
    done
    ffmpeg -loglevel error -y "${inputs[@]}" \
        -filter_complex "[0][1][2][3]hstack=inputs=4,scale=iw/2:-2" "$root/docs/images/gallery_$name.png"
    cp "$png" "$root/docs/images/gallery_${name}_still.png"
done

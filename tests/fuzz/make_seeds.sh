#!/usr/bin/env bash
# Regenerates the seed corpora in tests/fuzz/corpus/ from the shipped and test graphs and with
# the CLI. Run it again when a file format changes, and commit the result.
# Usage: tests/fuzz/make_seeds.sh [CLI]   (default: build/cli/cloudgraph)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cli=${1:-"$root/build/cli/cloudgraph"}
corpus="$here/corpus"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# graph_loader: every shipped graph, every good and bad test graph.
rm -rf "$corpus/graph_loader" && mkdir -p "$corpus/graph_loader"
for f in "$root"/graphs/*.json; do cp "$f" "$corpus/graph_loader/graphs_$(basename "$f")"; done
for f in "$root"/tests/data/good/*.json; do cp "$f" "$corpus/graph_loader/good_$(basename "$f")"; done
for f in "$root"/tests/data/bad/*.json; do
    [ "$(basename "$f")" = expected.json ] && continue  # the table of expected errors
    cp "$f" "$corpus/graph_loader/bad_$(basename "$f")"
done

# cgp_reader: a small primitive set (50 frames, 43 positions) and an empty one-frame set.
rm -rf "$corpus/cgp_reader" && mkdir -p "$corpus/cgp_reader"
"$cli" run "$here/seed_primitive.json" --out "$work/p" -q
cp "$work/p/small.cgp" "$corpus/cgp_reader/sim50_thin6.cgp"
"$cli" run "$here/seed_primitive.json" --out "$work/p1" -q --set sim.frames=1
cp "$work/p1/small.cgp" "$corpus/cgp_reader/sim1_empty.cgp"

# cache_entry: the payload (what follows the 56-byte header) of the smallest entry for each
# set of port types, and an empty fog volume.
rm -rf "$corpus/cache_entry" && mkdir -p "$corpus/cache_entry"
"$cli" run "$here/seed_cache_values.json" --out "$work/v" --cache "$work/c" -q
"$cli" run "$here/seed_cache_values.json" --out "$work/e" --cache "$work/ce" -q \
    --set voxelize.voxelSize=100 --set voxelize.radius=1
python3 - "$corpus/cache_entry" "$work/c" "" "$work/ce" "_empty" <<'PY'
import glob, os, struct, sys

def types(payload):
    count, = struct.unpack_from('<Q', payload, 0)
    at, names = 8, set()
    for _ in range(count):
        for field in ('port', 'type', 'data'):
            n, = struct.unpack_from('<Q', payload, at)
            if field == 'type': names.add(payload[at + 8:at + 8 + n].decode())
            at += 8 + n
    return '-'.join(sorted(names))

out = sys.argv[1]
for cache, suffix in zip(sys.argv[2::2], sys.argv[3::2]):
    best = {}
    for path in glob.glob(cache + '/objects/*/*.cgc'):
        payload = open(path, 'rb').read()[56:]
        name = types(payload)
        if suffix and name != 'FogVolume': continue
        if name not in best or len(payload) < len(best[name]): best[name] = payload
    for name, payload in best.items():
        open(f'{out}/{name}{suffix}.payload', 'wb').write(payload)
PY
# plugin_stamp: the test plugins (stamped, wrong ABI, no entry), stripped (~14 KB each; the
# section headers the reader parses sit at the end of the file).
rm -rf "$corpus/plugin_stamp" && mkdir -p "$corpus/plugin_stamp"
plugins="$(dirname "$cli")/../plugins"
for p in sample bad_abi no_entry; do
    strip -o "$corpus/plugin_stamp/$p.so" "$plugins/libcloudgraph_${p}_plugin.so"
done

# sounding_reader: the test soundings in both formats.
rm -rf "$corpus/sounding_reader" && mkdir -p "$corpus/sounding_reader"
cp "$root"/tests/data/soundings/* "$corpus/sounding_reader/"

# chan_reader: a written camera and one with comments and seven columns.
rm -rf "$corpus/chan_reader" && mkdir -p "$corpus/chan_reader"
printf '0 3200 2000 6500 -8.5 0 0 45\n1 3201.5 2000 6499 -8.4 0.1 0 44.5\n' \
    >"$corpus/chan_reader/written.chan"
printf '# from Nuke\n\n1\t0 1 2\t10 20 30\r\n2 0 1 2 10 20 30 39.5\n' \
    >"$corpus/chan_reader/comments.chan"

# map_reader: a WriteMap PFM and its 16-bit PNG preview.
rm -rf "$corpus/map_reader" && mkdir -p "$corpus/map_reader"
cat >"$work/map.json" <<'JSON'
{"cloudgraph": 1, "nodes": {"noise": {"type": "NoiseMap", "params": {"width": 6, "height": 4}},
 "write": {"type": "WriteMap", "inputs": {"map": "noise.map"}, "params": {"file": "m.pfm"}}}}
JSON
"$cli" run "$work/map.json" --out "$work/map" -q
cp "$work/map/m.pfm" "$work/map/m.png" "$corpus/map_reader/"

# vdb_reader: a one-leaf fog volume written by WriteVDB as full floats (blosc) and half floats
# (zip), an empty grid, a level set sphere (vdb_tool, from libopenvdb-tools) and an empty file.
rm -rf "$corpus/vdb_reader" && mkdir -p "$corpus/vdb_reader"
"$cli" run "$here/seed_vdb.json" --out "$work/vdb" -q
for f in full half empty_grid; do cp "$work/vdb/$f.vdb" "$corpus/vdb_reader/$f.vdb"; done
vdb_tool -quiet -sphere dim=8 radius=1 name=density -write "$corpus/vdb_reader/level_set.vdb"
: > "$corpus/vdb_reader/empty_file.vdb"

ls -l "$corpus"/*

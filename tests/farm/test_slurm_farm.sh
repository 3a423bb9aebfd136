#!/usr/bin/env bash
# The render farm on a real Slurm (docs/farm.md), ctest label "slurm": a one-node cluster on
# localhost renders tests/farm/farm_cloud.json in chunks with `cloudgraph farm --submit`;
# every file must equal a single-machine run of the same graph, byte for byte. Then one
# array task is killed (SIGKILL) mid-chunk and resubmitted: the rerun must skip the frames
# the killed task finished (their files verify) and cook the rest, again to the same bytes.
# Usage: test_slurm_farm.sh CLOUDGRAPH WORK_DIR
set -euo pipefail
cg=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
graph=$here/farm_cloud.json
size=(--set render.width=480 --set render.height=360)  # ~0.3 s a frame: time to kill mid-chunk
chunk=20                                               # frames 0-59: tasks 0, 1, 2

rm -rf "$work"
mkdir -p "$work"
trap '"$here/slurm_cluster.sh" stop "$work/cluster"' EXIT
SLURM_CONF=$("$here/slurm_cluster.sh" start "$work/cluster")
export SLURM_CONF

fail() { echo "FAIL: $*" >&2; exit 1; }

# Waits until job $1 (every task of an array) has left the queue; prints its task states.
wait_for_job() {
    for _ in $(seq 3000); do
        states=$(scontrol show job -o "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort | uniq -c || true)
        if [ -n "$states" ] && ! grep -qE 'PENDING|RUNNING|CONFIGURING|COMPLETING' <<<"$states"; then
            echo "$states"
            return 0
        fi
        sleep 0.2
    done
    fail "job $1 did not finish in 10 minutes: $(scontrol show job -o "$1")"
}

completed() { ! grep -v 'JobState=COMPLETED$' <<<"$1" | grep -q .; }  # wait_for_job's states

same_files() {  # same_files DIR_A DIR_B: the same names with the same bytes
    diff <(cd "$1" && find . -type f | sort) <(cd "$2" && find . -type f | sort) ||
        fail "$1 and $2 hold different files"
    (cd "$1" && find . -type f -print0 | while IFS= read -r -d '' f; do
        cmp -s "$f" "$2/$f" || { echo "differs: $f" >&2; exit 1; }
    done) || fail "$1 and $2 differ"
}

echo "== one machine"
"$cg" run "$graph" "${size[@]}" --out "$work/single" -q

echo "== the farm: simulate, $chunk-frame chunks, finish"
"$cg" farm "$graph" "${size[@]}" --chunk $chunk --cache "$work/cache" --out "$work/farm" --submit \
    | tee "$work/submitted.txt"
ids=$(awk '/^(simulate|frames|finish) job/ {print $3}' "$work/submitted.txt")
[ "$(wc -w <<<"$ids")" -eq 3 ] || fail "farm --submit did not print three job ids"
for id in $ids; do
    states=$(wait_for_job "$id")
    completed "$states" || fail "job $id: $states"
done
same_files "$work/single/cloud" "$work/farm/cloud"
python3 - "$work/farm/slurm/reports" <<'PY'
import json, sys
reports = sys.argv[1]
for task in range(3):
    r = json.load(open(f"{reports}/frames-{task}.json"))
    assert r["frames"] == [20 * task, 20 * task + 19], r["frames"]
    # Each task starts from the cached state before its first frame: no simulation step cooks.
    sims = [x for x in r["records"] if x["type"] in ("ThermalIntegrator", "Condensation")]
    assert sims and all(x["status"] != "cooked" for x in sims), "a chunk stepped a simulation"
    assert not any(x["type"] == "EncodeVideo" for x in r["records"]), "a chunk ran EncodeVideo"
    images = [x["status"] for x in r["records"] if x["type"] == "WriteImage"]
    assert images == ["cooked"] * 20, images
r = json.load(open(f"{reports}/finish.json"))
statuses = {(x["type"], x["status"]) for x in r["records"] if x["type"] in ("WriteImage", "EncodeVideo")}
# The finish job finds every frame written, and only encodes.
assert statuses == {("WriteImage", "verified"), ("EncodeVideo", "cooked")}, statuses
print("reports: each chunk renders its frames from cached states, the finish job only encodes")
PY

echo "== kill task 2 mid-chunk, resubmit it"
# A cache of its own, so that the renders are not cache hits from the run above.
"$cg" farm "$graph" "${size[@]}" --chunk $chunk --cache "$work/cache-killed" --out "$work/killed"
simulate=$(sbatch --parsable "$work/killed/slurm/simulate.sbatch")
job=$(sbatch --parsable --dependency=afterok:"${simulate%%;*}" --array=2 "$work/killed/slurm/frames.sbatch")
job=${job%%;*}
for _ in $(seq 15000); do  # until the task has written its second frame (5 minutes at most)
    [ -f "$work/killed/cloud/frame.0041.png" ] && break
    sleep 0.02
done
scancel --signal=KILL --full "${job}_2"
wait_for_job "$job" >/dev/null
written=$(find "$work/killed/cloud" -name 'frame.*.png' | wc -l)
echo "the killed task had written $written of 20 frames"
{ [ "$written" -ge 1 ] && [ "$written" -lt 20 ]; } || fail "the kill did not land mid-chunk ($written frames)"
job=$(sbatch --parsable --array=2 "$work/killed/slurm/frames.sbatch")
states=$(wait_for_job "${job%%;*}")
completed "$states" || fail "the resubmitted task: $states"
python3 - "$work/killed/slurm/reports/frames-2.json" "$written" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
images = {x["frame"]: x["status"] for x in r["records"] if x["type"] == "WriteImage"}
verified = sum(s == "verified" for s in images.values())
cooked = sum(s == "cooked" for s in images.values())
assert verified >= int(sys.argv[2]) - 1 and cooked >= 1 and verified + cooked == 20, images
print(f"rerun: {verified} frames verified and skipped, {cooked} cooked")
PY
mkdir -p "$work/single-chunk2"
for f in "$work"/single/cloud/*.00[45][0-9].*; do cp "$f" "$work/single-chunk2/"; done
same_files "$work/single-chunk2" "$work/killed/cloud"
echo "PASS"

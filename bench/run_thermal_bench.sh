#!/usr/bin/env bash
# Runs the integrator benchmark and prints the medians and their ratio to the copy peer.
# Usage: bench/run_thermal_bench.sh [BUILD_DIR]   (a Release build)
set -euo pipefail
build=${1:-build}
out=$(mktemp)
"$build/bench/thermal_bench" --benchmark_repetitions=7 --benchmark_report_aggregates_only=true \
    --benchmark_format=json > "$out"
python3 - "$out" <<'PY'
import json, sys
runs = {b["run_name"]: b for b in json.load(open(sys.argv[1]))["benchmarks"] if b["aggregate_name"] == "median"}
step, copy = runs["BM_ThermalStep/real_time"], runs["BM_StreamCopy/real_time"]
print(f"ThermalStep: {step['items_per_second']/1e6:.0f} M particle-steps/s, {step['bytes_per_second']/1e9:.2f} GB/s")
print(f"StreamCopy:  {copy['bytes_per_second']/1e9:.2f} GB/s (same bytes)")
print(f"ratio: {step['bytes_per_second']/copy['bytes_per_second']:.2f} of the copy bandwidth")
PY
rm -f "$out"

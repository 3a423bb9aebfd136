#!/usr/bin/env python3
"""The paper's Table 1 for our figure graphs, measured on this machine.

Usage: bench/run_table1.py BUILD_DIR [GRAPH ...]   (default: every graphs/figure*.json)

For each graph: cloud particles at the final step, steps, the time of simulation + mapping
(the paper's measure: the stochastic simulation, the mapper and the generation of every
frame's cloud-particle positions, primitive excluded), then voxelizing and rendering
separately (sums of the nodes' own times in a full run), and the peak resident memory of
each run. The primitive is built once and read back with PrimitiveLoad, as the paper
excludes it from its timings.
"""
import copy
import json
import os
import subprocess
import sys
import tempfile
import time

from bench_args import build_and_graphs

PAPER = {  # Table 1: cloud particles, seconds, steps (Pentium 4, 3.8 GHz)
    "figure1_cloudscape": (1592646, 359.0, 488),
    "figure5_progress": (4534381, 559.0, 612),
    "figure6_towering_cumulus": (492646, 159.6, 491),
    "figure7a_beta33": (1405644, 354.0, 500),
    "figure7b_beta27": (1707802, 380.8, 503),
    "figure8_cumulonimbus": (1973087, 423.9, 500),
}
DISPLAY_TYPES = {"Voxelizer", "Renderer", "WriteImage", "EncodeVideo", "WriteVDB", "WritePoints",
                 "WriteCloudParticles", "WriteText", "LogText", "VapourPoints", "CombineVolumes"}


def run(cli, graph_path, out, report):
    """Runs the CLI as a child; returns (wall seconds, that child's peak RSS in bytes)."""
    t0 = time.monotonic()
    child = subprocess.Popen([cli, "run", graph_path, "--out", out, "--report", report, "-q"])
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    wall = time.monotonic() - t0
    if child.returncode != 0:
        sys.exit(f"{graph_path}: cloudgraph exited with {child.returncode}")
    return wall, usage.ru_maxrss * 1024


def node_seconds(report, types):
    return sum(r["seconds"] for r in report["records"] if r["type"] in types)


def main():
    build, graphs = build_and_graphs()
    cli = os.path.join(build, "cli", "cloudgraph")
    work = tempfile.mkdtemp(prefix="table1-")
    primitive = os.path.join(work, "primitive.cgp")
    prim_graph = os.path.join(work, "primitive.json")
    with open(prim_graph, "w") as f:
        json.dump({"cloudgraph": 1, "frames": {"start": 0, "end": 0}, "nodes": {
            "sim": {"type": "PrimitiveSim"},
            "write": {"type": "WritePrimitive", "inputs": {"primitive": "sim.primitive"},
                      "params": {"file": "primitive.cgp"}}}}, f)
    t0 = time.monotonic()
    subprocess.run([cli, "run", prim_graph, "--out", work, "-q"], check=True)
    print(f"primitive (PrimitiveSim defaults): {time.monotonic() - t0:.1f} s, once for all graphs")
    print()
    print("| graph | cloud particles (paper) | steps (paper) | sim + mapping s (paper) | "
          "voxelize s | render s | peak RSS, sim+map / full |")
    print("|---|---|---|---|---|---|---|")
    for path in graphs:
        name = os.path.splitext(os.path.basename(path))[0]
        with open(path) as f:
            graph = json.load(f)
        for node in graph["nodes"].values():
            if node["type"] == "PrimitiveSim":
                node.clear()
                node.update({"type": "PrimitiveLoad", "params": {"file": primitive}})
        mapping_only = copy.deepcopy(graph)
        mapping_only["nodes"] = {k: v for k, v in graph["nodes"].items() if v["type"] not in DISPLAY_TYPES}
        paths = {}
        for tag, g in (("map", mapping_only), ("full", graph)):
            paths[tag] = os.path.join(work, f"{name}.{tag}.json")
            with open(paths[tag], "w") as f:
                json.dump(g, f)
        map_wall, map_rss = run(cli, paths["map"], os.path.join(work, "out"), os.path.join(work, "map.json"))
        with open(os.path.join(work, "map.json")) as f:
            report = json.load(f)
        last = graph["frames"]["end"]
        count = next(r["values"]["cloudCount"] for r in report["records"]
                     if r["type"] == "PrimitiveMapper" and r["frame"] == last)
        _, full_rss = run(cli, paths["full"], os.path.join(work, "out"), os.path.join(work, "full.json"))
        with open(os.path.join(work, "full.json")) as f:
            full = json.load(f)
        vox = node_seconds(full, {"Voxelizer"})
        ren = node_seconds(full, {"Renderer", "WriteImage"})
        paper = PAPER.get(name)
        p = (lambda i, fmt: format(paper[i], fmt)) if paper else (lambda i, fmt: "-")
        print(f"| {name} | {count:,} ({p(0, ',')}) | {last - graph['frames']['start'] + 1} ({p(2, 'd')}) | "
              f"{map_wall:.1f} ({p(1, '.1f')}) | {vox:.1f} | {ren:.1f} | "
              f"{map_rss / 2**20:.0f} / {full_rss / 2**20:.0f} MiB |", flush=True)
    print(f"\n(work files in {work})")


if __name__ == "__main__":
    main()

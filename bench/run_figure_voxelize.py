#!/usr/bin/env python3
"""Every figure graph's voxelize time with the smooth kernel (before issue 17) and the
gaussian kernel (the default since), and how much the picture moves between the two.

Usage: bench/run_figure_voxelize.py BUILD_DIR [GRAPH ...]   (default: every graphs/figure*.json)
       FRAMES=N bench/run_figure_voxelize.py ...           (frames a span; default 8)

For each graph, two spans of FRAMES frames (default 8), cooked in one process each: the
middle of its range and its end (where the clouds are largest). The simulation states are
cooked once into a cache shared by every graph (`run --simulations-only`); then each span
is cooked once per kernel (`--set NODE.kernel=...` on every Voxelizer of the graph), and
after each run the cache is put back as the simulations left it, so every run voxelizes and
renders (at half the graph's width and height). Voxelize seconds are the Voxelizer nodes' own times from the run reports, summed
over the frames. The picture: each frame is also written as a linear EXR, and
build/bench/image_error gives the gaussian kernel's luminance error against the smooth
kernel's over the cloud pixels (mean and 90th percentile, the measure of
docs/rendering.md), at the last frame.
"""
import json
import os
import re
import shutil
import subprocess
import tempfile

from bench_args import build_and_graphs

KERNELS = ("smooth", "gaussian")


def files_under(directory):
    out = set()
    for parent, _, names in os.walk(directory):
        out.update(os.path.join(parent, n) for n in names)
    return out


def restore(cache, kept):
    """Removes what runs added to the cache since the simulations filled it."""
    for path in files_under(cache) - kept:
        os.remove(path)


def bench_copy(path, work):
    """The graph with its input files made absolute and an EXR writer on the render."""
    with open(path) as f:
        graph = json.load(f)
    base = os.path.dirname(os.path.abspath(path))
    for node in graph["nodes"].values():
        for key, value in node.get("params", {}).items():
            if isinstance(value, str) and os.path.isfile(os.path.join(base, value)):
                node["params"][key] = os.path.join(base, value)
    graph["nodes"]["benchExr"] = {"type": "WriteImage", "inputs": {"image": "render.image"},
                                  "params": {"file": "bench/frame.####.exr"}}
    copy = os.path.join(work, os.path.basename(path))
    with open(copy, "w") as f:
        json.dump(graph, f, indent=1)
    return copy, graph


def main():
    build, graphs = build_and_graphs()
    cli = os.path.join(build, "cli", "cloudgraph")
    image_error = os.path.join(build, "bench", "image_error")
    work = tempfile.mkdtemp(prefix="figure-voxelize-")
    cache = os.path.join(work, "cache")
    print("| graph | frames | voxelize smooth s | voxelize gaussian s | "
          "speed-up | last frame: mean / p90 luminance difference |")
    print("|---|---|---|---|---|---|")
    total = {k: 0.0 for k in KERNELS}
    try:
        for path in graphs:
            name = os.path.splitext(os.path.basename(path))[0]
            copy, graph = bench_copy(path, work)
            voxelizers = [n for n, v in graph["nodes"].items() if v["type"] == "Voxelizer"]
            videos = [n for n, v in graph["nodes"].items() if v["type"] == "EncodeVideo"]
            # Renders at half the width and height: the voxelizer is timed, the picture compared.
            halves = [f"{n}.{k}={v['params'][k] // 2}" for n, v in graph["nodes"].items()
                      if v["type"] == "Renderer" for k in ("width", "height") if k in v.get("params", {})]
            end = graph["frames"]["end"]
            span = int(os.environ.get("FRAMES", "8"))
            spans = [(end // 2 - span + 1, end // 2), (end - span + 1, end)]
            subprocess.run([cli, "run", copy, "--simulations-only", "--cache", cache,
                            "--out", os.path.join(work, "out"), "-q"], check=True)
            kept = files_under(cache)
            seconds = {k: 0.0 for k in KERNELS}
            for kernel in KERNELS:
                for first, frame in spans:
                    out = os.path.join(work, kernel)
                    report = os.path.join(work, "report.json")
                    sets = [f"{v}.kernel={kernel}" for v in voxelizers] + halves
                    sets += [f"{v}.firstFrame={first}" for v in videos]
                    sets += [f"{v}.lastFrame={frame}" for v in videos]
                    argv = [cli, "run", copy, "--frames", f"{first}:{frame}", "--cache", cache,
                            "--out", out, "--report", report, "-q"]
                    for s in sets:
                        argv += ["--set", s]
                    subprocess.run(argv, check=True)
                    restore(cache, kept)
                    with open(report) as f:
                        records = json.load(f)["records"]
                    seconds[kernel] += sum(r["seconds"] for r in records if r["type"] == "Voxelizer")
            last = f"bench/frame.{end:04d}.exr"
            error = subprocess.run([image_error, os.path.join(work, "gaussian", last),
                                    os.path.join(work, "smooth", last)],
                                   check=True, capture_output=True, text=True).stdout
            mean = float(re.search(r"mean=(\S+)", error).group(1))
            p90 = float(re.search(r"p90=(\S+)", error).group(1))
            for k in KERNELS:
                total[k] += seconds[k]
            print(f"| {name} | {', '.join(f'{a}-{b}' for a, b in spans)} | "
                  f"{seconds['smooth']:.2f} | {seconds['gaussian']:.2f} | "
                  f"**{seconds['smooth'] / seconds['gaussian']:.1f}x** | "
                  f"{100 * mean:.2f}% / {100 * p90:.2f}% |", flush=True)
        print(f"| all | | {total['smooth']:.2f} | {total['gaussian']:.2f} | "
              f"**{total['smooth'] / total['gaussian']:.1f}x** | |")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

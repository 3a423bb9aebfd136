#!/usr/bin/env python3
"""Every figure graph's voxelize time with the smooth kernel (before issue 17) and the
gaussian kernel (the default since), and how much the picture moves between the two.

Usage: bench/run_figure_voxelize.py BUILD_DIR [GRAPH ...]   (default: every graphs/figure*.json)
       FRAMES=N REPEAT=R bench/run_figure_voxelize.py ...  (frames a span, default 8; runs, default 3)

For each graph, two spans of FRAMES frames (default 8), cooked in one process each: the
middle of its range and its end (where the clouds are largest). The simulation states are
cooked once into a cache shared by every graph (`run --simulations-only`); then each span
is cooked once per kernel (`--set NODE.kernel=...` on every Voxelizer of the graph), and
after each run the cache is put back as the simulations left it, so every run voxelizes.
Voxelize seconds are the Voxelizer nodes' own times from the run reports, summed over the
frames of a span; each span is run REPEAT times, the kernels taking turns, and its median
counts. The timing runs leave out the Renderers and what depends on them: on two cores a
render of one frame beside the voxelization of the next would be timed as the Voxelizer's.
The picture: the last frame is cooked once more per kernel with the Renderers (at half the
graph's width and height) and written as a linear EXR, and build/bench/image_error gives
the gaussian kernel's luminance error against the smooth kernel's over the cloud pixels
(mean and 90th percentile, the measure of docs/rendering.md).
"""
import json
import os
import re
import shutil
import statistics
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


def downstream_of_renderers(graph):
    """The Renderer nodes and every node that reads from them, directly or not."""
    nodes = graph["nodes"]
    out = {n for n, v in nodes.items() if v["type"] == "Renderer"}
    grew = True
    while grew:
        grew = False
        for n, v in nodes.items():
            sources = {str(s).split(".")[0] for s in v.get("inputs", {}).values()}
            if n not in out and sources & out:
                out.add(n)
                grew = True
    return out


def bench_copy(path, work):
    """The graph with its input files made absolute and an EXR writer on the render, and a
    copy without the renderers' branch for the timing runs."""
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
    unrendered = {k: v for k, v in graph.items() if k != "nodes"}
    skipped = downstream_of_renderers(graph)
    unrendered["nodes"] = {n: v for n, v in graph["nodes"].items() if n not in skipped}
    timing_copy = os.path.join(work, "timing-" + os.path.basename(path))
    with open(timing_copy, "w") as f:
        json.dump(unrendered, f, indent=1)
    return copy, timing_copy, graph


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
            copy, timing_copy, graph = bench_copy(path, work)
            voxelizers = [n for n, v in graph["nodes"].items() if v["type"] == "Voxelizer"]
            videos = [n for n, v in graph["nodes"].items() if v["type"] == "EncodeVideo"]
            # Renders at half the width and height: the picture is compared, not timed.
            halves = [f"{n}.{k}={v['params'][k] // 2}" for n, v in graph["nodes"].items()
                      if v["type"] == "Renderer" for k in ("width", "height") if k in v.get("params", {})]
            end = graph["frames"]["end"]
            span = int(os.environ.get("FRAMES", "8"))
            repeat = int(os.environ.get("REPEAT", "3"))
            spans = [(end // 2 - span + 1, end // 2), (end - span + 1, end)]
            subprocess.run([cli, "run", copy, "--simulations-only", "--cache", cache,
                            "--out", os.path.join(work, "out"), "-q"], check=True)
            kept = files_under(cache)

            def cook(kernel, graph_file, first, last, extra=()):
                """Voxelize seconds of one run of frames first..last with `kernel`."""
                report = os.path.join(work, "report.json")
                sets = [f"{v}.kernel={kernel}" for v in voxelizers] + list(extra)
                argv = [cli, "run", graph_file, "--frames", f"{first}:{last}", "--cache", cache,
                        "--out", os.path.join(work, kernel), "--report", report, "-q"]
                for s in sets:
                    argv += ["--set", s]
                subprocess.run(argv, check=True)
                restore(cache, kept)
                with open(report) as f:
                    records = json.load(f)["records"]
                return sum(r["seconds"] for r in records if r["type"] == "Voxelizer")

            runs = {(k, s): [] for k in KERNELS for s in spans}
            for _ in range(repeat):
                for first, last in spans:
                    for kernel in KERNELS:
                        runs[(kernel, (first, last))].append(cook(kernel, timing_copy, first, last))
            seconds = {k: sum(statistics.median(runs[(k, s)]) for s in spans) for k in KERNELS}
            for kernel in KERNELS:
                cook(kernel, copy, end, end,
                     halves + [f"{v}.firstFrame={end}" for v in videos] +
                     [f"{v}.lastFrame={end}" for v in videos])
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

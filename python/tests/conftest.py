"""Shared fixtures: a Figure 6 graph shrunk to cook in a fraction of a second (the golden
tests' reductions: the small primitive, a coarser map and voxels, a thumbnail render)."""

import json
import os
import pathlib

import pytest

import cloudgraph

SOURCE = pathlib.Path(__file__).resolve().parents[2]
FIGURE6 = SOURCE / "graphs" / "figure6_towering_cumulus.json"


def shrink(graph):
    for name, value in dict(frames=40, width=400.0, height=700.0, sourceHeight=100.0,
                            sourceRadius=125.0, sourceHumidity=1.0).items():
        graph["primitive"].params[name] = value
    noise = graph["noise"].params
    noise["cellSize"] = noise["cellSize"] * 2
    noise["width"] = noise["width"] // 2
    noise["height"] = noise["height"] // 2
    noise["largestWavelength"] = noise["largestWavelength"] / 2
    graph["voxelize"].params["voxelSize"] = graph["voxelize"].params["voxelSize"] * 2
    graph["render"].params["width"] = 96
    graph["render"].params["height"] = 64
    return graph


@pytest.fixture
def small_figure6():
    return shrink(cloudgraph.Graph.load(FIGURE6))


@pytest.fixture
def small_figure6_file(tmp_path, small_figure6):
    """The small graph as a file beside the run's folders (its PLY writer left out: the
    tests compare images and volumes)."""
    path = tmp_path / "small_figure6.json"
    small_figure6.save(path)
    return path


@pytest.fixture
def cli():
    return os.environ["CLOUDGRAPH_CLI"]


def statuses(report, frame):
    return {r["node"]: r["status"] for r in report["records"] if r["frame"] == frame}

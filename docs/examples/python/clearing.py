"""A density map edited in NumPy and fed back: a clearing in Figure 6's map, where no vapour
rises, so the cumulus grows as a ring around it.
Run from the repository root: python3 docs/examples/python/clearing.py [GRAPH]"""

import sys

import numpy as np

import cloudgraph


@cloudgraph.node
class Clearing:
    """Sets a density map to 0 inside a disc: no vapour is emitted there (Eq. 9's fNoise)."""
    inputs = {"map": cloudgraph.Input("Map2D", "the density map fNoise")}
    outputs = {"map": cloudgraph.Output("Map2D", "the map with the clearing")}
    params = {
        "centreX": cloudgraph.Param(float, 0.0, units="m", doc="x of the disc's centre"),
        "centreY": cloudgraph.Param(float, 0.0, units="m", doc="y of the disc's centre"),
        "radius": cloudgraph.Param(float, 1000.0, min=0, units="m", doc="the disc's radius"),
    }

    def cook(self, inputs, params, context):
        density = inputs["map"]
        values = np.array(density.values)  # a writable copy of the read-only view
        ny, nx = values.shape
        y, x = (np.mgrid[0:ny, 0:nx] + 0.5) * density.cell_size  # cell centres, metres
        inside = np.hypot(x - params["centreX"], y - params["centreY"]) < params["radius"]
        values[inside] = 0.0
        return {"map": cloudgraph.Map2D(values, density.cell_size)}


def with_clearing(graph, radius):
    """The graph with a Clearing between the noise map and everything that reads it."""
    noise = graph["noise"].params
    graph.add_node("clearing", "Clearing", {
        "centreX": noise["width"] * noise["cellSize"] / 2,
        "centreY": noise["height"] * noise["cellSize"] / 2,
        "radius": radius,
    })
    graph.connect("noise.map", "clearing.map")
    graph.connect("clearing.map", "emit.map")  # replaces the wire from noise.map
    graph.connect("clearing.map", "mapper.map")
    return graph


if __name__ == "__main__":
    path = sys.argv[1] if len(sys.argv) > 1 else "graphs/figure6_towering_cumulus.json"
    graph = with_clearing(cloudgraph.Graph.load(path), radius=1000.0)
    image = graph.cook("render.image", frame=400, cache="out/cache")
    cloudgraph.write_image("out/clearing.png", image)

"""A wedge: the still cumulus under nine sun directions, as one 3 x 3 contact sheet (PNG).
Run from the repository root: python3 docs/examples/python/contact_sheet.py"""

import math

import numpy as np

import cloudgraph

graph = cloudgraph.Graph.load("graphs/cumulus_still.json")
render = graph["render"].params
render["width"], render["height"] = 240, 180

tiles = []
for i in range(9):
    azimuth = 2 * math.pi * i / 9
    render["sunDirection"] = [math.cos(azimuth), math.sin(azimuth), 0.6]
    # The cloud comes from the cache after the first cook: only the Renderer cooks again.
    tiles.append(graph.cook("render.image", cache="out/cache"))

rows = [np.concatenate(tiles[3 * r:3 * r + 3], axis=1) for r in range(3)]
cloudgraph.write_image("out/sun_wedge.png", np.concatenate(rows, axis=0))

"""CloudGraph from Python: load, build and edit graphs, cook any output into NumPy arrays,
write node types in Python, with the same validation, errors and content-keyed caches as the
`cloudgraph` CLI. See docs/python.md."""

from .errors import Cancelled, CookError, Error, FileError, GraphError, ParameterError
from .graph import Graph, Node
from .nodes import Input, Output, Param, node
from .types import NodeType, node_types
from ._cloudgraph import CloudParticles, FogVolume, Map2D, Value, write_image

__all__ = [
    "Graph", "Node", "NodeType", "node_types",
    "node", "Input", "Output", "Param",
    "CloudParticles", "FogVolume", "Map2D", "Value", "write_image",
    "Error", "GraphError", "ParameterError", "FileError", "CookError", "Cancelled",
]

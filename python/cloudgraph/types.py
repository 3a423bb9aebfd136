"""The node types the engine knows, as Python objects made from their C++ declarations."""

import functools
import json
from dataclasses import dataclass
from typing import Any, Dict, List, Optional

from . import _cloudgraph


@dataclass(frozen=True)
class Port:
    name: str
    type: str
    doc: str
    optional: bool


@dataclass(frozen=True)
class Param:
    name: str
    type: str  # float, int, bool, string, vec3, float list, int list
    default: Any
    min: Optional[float]
    max: Optional[float]
    units: str
    doc: str
    role: str  # plain, input_file, output_path, program
    choices: List[str]


@dataclass(frozen=True)
class NodeType:
    type: str
    version: int
    category: str
    doc: str
    inputs: List[Port]
    outputs: List[Port]
    params: Dict[str, Param]
    frame_dependent: bool
    simulation: bool
    writes_files: bool


def _node_type(d):
    return NodeType(
        type=d["type"], version=d["version"], category=d["category"], doc=d["doc"],
        inputs=[Port(**p) for p in d["inputs"]], outputs=[Port(**p) for p in d["outputs"]],
        params={p["name"]: Param(**p) for p in d["params"]},
        frame_dependent=d["frame_dependent"], simulation=d["simulation"],
        writes_files=d["writes_files"])


@functools.lru_cache(maxsize=None)
def _declarations():
    return {d["type"]: _node_type(d) for d in json.loads(_cloudgraph.node_types_json())}


def declarations_changed():
    """A node type was registered (cloudgraph.node): forget the declarations read so far."""
    _declarations.cache_clear()


def node_types() -> Dict[str, NodeType]:
    """Every node type by name, with its ports and parameters (defaults, ranges, units)."""
    return dict(_declarations())

"""Custom nodes written in Python: declare ports and parameters once, as C++ nodes do, and a
cook(inputs, params, context) that returns the outputs. Such a node takes part in keys,
caches and run reports like any other, from Python and from JSON graphs the CLI runs with
`--python-nodes module.py`. See docs/python.md, "Custom nodes"."""

import hashlib
import importlib.util
import inspect
import json
import marshal
import os
import sys
from dataclasses import dataclass, field
from typing import Any, List, Optional

from . import _cloudgraph, types

# Parameter types by the engine's names (types.py) and by the Python types that map to them.
_PARAM_TYPES = {"float": "float", "int": "int", "bool": "bool", "string": "string",
                "vec3": "vec3", "float list": "float list", "int list": "int list",
                float: "float", int: "int", bool: "bool", str: "string"}


@dataclass(frozen=True)
class Input:
    """An input port: its data type (a registered name: "Image", "Map2D", "Float", ...)."""
    type: str
    doc: str
    optional: bool = False


@dataclass(frozen=True)
class Output:
    """An output port. Python values are converted as docs/python.md's table says."""
    type: str
    doc: str


@dataclass(frozen=True)
class Param:
    """A parameter: type ("float", "int", "bool", "string", "vec3", "float list",
    "int list", or float/int/bool/str), default, inclusive range, units, one line of doc,
    allowed choices of a string, and role ("plain", or "input_file" for a file the node
    reads: its content, not its name, goes into the node's cache key)."""
    type: Any
    default: Any
    min: Optional[float] = None
    max: Optional[float] = None
    units: str = ""
    doc: str = ""
    choices: List[str] = field(default_factory=list)
    role: str = "plain"


class Context:
    """What a cook may know besides its inputs and parameters. `frame`, `start_frame`,
    `time_step` and `seed` are there only if the class declares it reads them
    (frame_dependent, reads_time_step, reads_seed): what a node reads must be in its key."""

    def __init__(self, node_id, declared, frame, start_frame, time_step, seed):
        self.node_id = node_id
        self._declared = declared
        self._values = dict(frame=frame, start_frame=start_frame, time_step=time_step, seed=seed)

    def __getattr__(self, name):
        flag = {"frame": "frame_dependent", "start_frame": "frame_dependent",
                "time_step": "reads_time_step", "seed": "reads_seed"}.get(name)
        if flag is None:
            raise AttributeError(name)
        if not getattr(self._declared, flag, False):
            raise AttributeError(f"node '{self.node_id}' reads context.{name} but its class "
                                 f"{self._declared.__name__} does not declare {flag} = True")
        return self._values[name]


_registered = {}  # type name -> the class whose cook runs


def _ports(declared, kind):
    ports = []
    for name, port in (declared or {}).items():
        if not isinstance(port, kind):
            raise TypeError(f"port '{name}' is declared by a {type(port).__name__}, "
                            f"not cloudgraph.{kind.__name__}(type, doc)")
        ports.append(dict(name=name, type=port.type, doc=port.doc,
                          optional=getattr(port, "optional", False)))
    return ports


def _params(declared):
    params = []
    for name, p in (declared or {}).items():
        if p.type not in _PARAM_TYPES:
            raise ValueError(f"parameter '{name}': unknown type {p.type!r}")
        default = p.default.tolist() if hasattr(p.default, "tolist") else p.default
        params.append(dict(name=name, type=_PARAM_TYPES[p.type], default=default, min=p.min,
                           max=p.max, units=p.units, doc=p.doc, choices=list(p.choices),
                           role=p.role))
    return params


def _source_hash(cls):
    """What the cache key knows of the code: the whole module's source where it has a file
    (so an edit to a helper beside the class re-keys it), else the class's source, else its
    cook's bytecode (a class typed at a prompt)."""
    module = sys.modules.get(cls.__module__)
    for source in (lambda: inspect.getsource(module), lambda: inspect.getsource(cls)):
        try:
            return hashlib.sha256(source().encode()).hexdigest()
        except (OSError, TypeError):
            pass
    return hashlib.sha256(marshal.dumps(cls.cook.__code__)).hexdigest()


def declaration(cls):
    """The class's declaration as the engine takes it (JSON)."""
    if not callable(getattr(cls, "cook", None)):
        raise TypeError(f"{cls.__name__} has no cook(self, inputs, params, context)")
    return json.dumps(dict(
        type=getattr(cls, "type", cls.__name__),
        version=int(getattr(cls, "version", 1)),
        category=getattr(cls, "category", "python"),
        doc=inspect.cleandoc(cls.__doc__ or ""),
        inputs=_ports(getattr(cls, "inputs", {}), Input),
        outputs=_ports(getattr(cls, "outputs", {}), Output),
        params=_params(getattr(cls, "params", {})),
        frame_dependent=bool(getattr(cls, "frame_dependent", False)),
        reads_time_step=bool(getattr(cls, "reads_time_step", False)),
        reads_seed=bool(getattr(cls, "reads_seed", False)),
        source_hash=_source_hash(cls)))


def node(cls):
    """Class decorator: registers a node type (named by `type`, else the class name) for
    every graph of this process. Registering the same declaration and code again is allowed
    (a module imported twice); a different one under a taken name is a GraphError."""
    type_name = getattr(cls, "type", cls.__name__)
    _cloudgraph.register_python_node(declaration(cls))
    _registered[type_name] = cls
    types.declarations_changed()
    return cls


def _cook(type_name, node_id, inputs, params, frame, start_frame, time_step, seed):
    """Called by the engine (holding the GIL): runs the class's cook and checks its result."""
    cls = _registered[type_name]
    context = Context(node_id, cls, frame, start_frame, time_step, seed)
    outputs = cls().cook(inputs, params, context)
    if not isinstance(outputs, dict):
        raise TypeError(f"cook() returned {type(outputs).__name__}, not a dict of outputs")
    return outputs


def load_file(path):
    """Runs a Python file of node classes (the CLI's --python-nodes) as a module named by its
    file name, so its @node classes register."""
    path = os.path.abspath(path)
    name = os.path.splitext(os.path.basename(path))[0]
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None:
        raise ImportError(f"not a Python file: {path}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module

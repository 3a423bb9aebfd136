"""cloudgraph.Graph: a graph document, edited with the loader's own checks and cooked by the
engine."""

import json
import math
import operator
import os
import tempfile
from collections.abc import MutableMapping

from . import _cloudgraph
from .errors import FileError, GraphError, ParameterError
from .types import node_types


def _plain(value):
    """A NumPy value or array, or a list holding NumPy values, as plain Python, for JSON."""
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    return value.tolist() if hasattr(value, "tolist") else value


def _with_pyopenvdb(volume):
    """The volume as a pyopenvdb.FloatGrid where pyopenvdb is installed (read back from a
    .vdb file: the two modules cannot hand a grid over in memory)."""
    try:
        import pyopenvdb
    except ImportError:
        return volume
    with tempfile.TemporaryDirectory(prefix="cloudgraph-") as d:
        path = os.path.join(d, "volume.vdb")
        volume.to_vdb(path)
        return pyopenvdb.read(path, "density")


def _as_file_error(error, graph_dict, types):
    """A ParameterError about a parameter that names a file to read (ReadVDB's file, a
    sounding) is a FileError: the file, not the value's type or range, is at fault."""
    where = error.where or ""
    param = where.partition("/params/")[2].split("/")[0]
    node_type = graph_dict.get("nodes", {}).get(error.node or "", {}).get("type")
    declared = types.get(node_type)
    if not param or declared is None or param not in declared.params:
        return error
    if declared.params[param].role != "input_file":
        return error
    converted = FileError(str(error))
    converted.where, converted.node = error.where, error.node
    return converted


def _checked(call, graph_dict, types):
    """call(), with a ParameterError about an input file raised as a FileError; graph_dict()
    gives the graph the error is about (asked for only then)."""
    try:
        return call()
    except ParameterError as error:
        converted = _as_file_error(error, graph_dict(), types)
        if converted is error:
            raise
        raise converted from None


def _non_finite(value, path=()):
    """(keys, value) of the first NaN or infinity in a plain value, or None."""
    if isinstance(value, float) and not math.isfinite(value):
        return path, value
    items = value.items() if isinstance(value, dict) else \
        enumerate(value) if isinstance(value, (list, tuple)) else ()
    for key, item in items:
        found = _non_finite(item, path + (key,))
        if found:
            return found
    return None


def _dumps(d, name):
    """A graph dict as JSON text. JSON cannot carry a NaN or infinity, so one is refused here
    by its place, as the loader words it (a ParameterError in a node's parameters), rather
    than as text that does not parse."""
    found = _non_finite(d)
    if found is None:
        return json.dumps(d)
    path, value = found
    node = path[1] if len(path) > 1 and path[0] == "nodes" else None
    pointer = "".join("/" + str(key).replace("~", "~0").replace("/", "~1") for key in path)
    where = f"{name}:{pointer}"
    text = "nan" if math.isnan(value) else "inf" if value > 0 else "-inf"
    in_params = node is not None and len(path) > 3 and path[2] == "params"
    error = (ParameterError if in_params else GraphError)(
        f"{where}: value {text} is not finite" + (f" (node '{node}')" if node else ""))
    error.where, error.node = where, node
    raise error


def _split(ref, what):
    node, dot, port = ref.partition(".")
    if not dot or not node or not port:
        raise GraphError(f"{what} '{ref}' is not 'node.port'")
    return node, port


class Params(MutableMapping):
    """A node's parameters: every declared one (its default unless set). Assigning checks
    type, range and choices as loading does, and raises ParameterError otherwise."""

    def __init__(self, graph, node_id):
        self._graph = graph
        self._id = node_id

    def _declared(self):
        return self._graph._type_of(self._id).params

    def __getitem__(self, name):
        node = self._graph._node_dict(self._id)
        declared = self._graph._types[node["type"]].params
        if name not in declared:
            raise KeyError(name)
        return node.get("params", {}).get(name, declared[name].default)

    def __setitem__(self, name, value):
        graph = self._graph
        _checked(lambda: graph._doc.set_param(self._id, name, _plain(value)), graph.to_dict,
                 graph._types)

    def __delitem__(self, name):
        self[name] = self._declared()[name].default

    def __iter__(self):
        return iter(self._declared())

    def __len__(self):
        return len(self._declared())

    def __repr__(self):
        return repr(dict(self))


class Node:
    """A node of a graph: its id, type, parameters and input wiring."""

    def __init__(self, graph, node_id):
        self._graph = graph
        self.id = node_id

    @property
    def type(self):
        return self._graph._node_dict(self.id)["type"]

    @property
    def params(self):
        return Params(self._graph, self.id)

    @property
    def inputs(self):
        """{input port: "node.port"} for each connected input."""
        return dict(self._graph._node_dict(self.id).get("inputs", {}))

    def __repr__(self):
        return f"<cloudgraph.Node {self.id} ({self.type})>"


class Graph:
    """A CloudGraph graph. Load one with Graph.load(path) or Graph.from_dict(d); edit it with
    add_node, connect, disconnect, remove_node and node parameters; cook any output with
    cook("node.port", frame)."""

    def __init__(self, document):
        self._doc = document

    @property
    def _types(self):
        return node_types()  # cached; includes Python nodes registered since

    @classmethod
    def load(cls, path):
        """Loads a graph file, validated as `cloudgraph validate` does. Raises FileError,
        GraphError or ParameterError naming the file and JSON pointer."""
        def read_dict():  # it parsed, or there would be no parameter error
            with open(path) as f:
                return json.load(f)
        return cls(_checked(lambda: _cloudgraph.Document.load(os.fspath(path)), read_dict, node_types()))

    @classmethod
    def from_dict(cls, d, name="<dict>", base_dir="."):
        """A graph from a dict in the file format; `name` prefixes error locations and
        relative input files are found under `base_dir`."""
        return cls(_checked(
            lambda: _cloudgraph.Document.parse(_dumps(d, name), name, os.fspath(base_dir)),
            lambda: d, node_types()))

    def to_dict(self):
        """The graph in the file format (every parameter that differs from its default)."""
        return json.loads(self._doc.to_json())

    def save(self, path):
        """Writes the graph to `path` atomically; refuses a graph with an unconnected
        required input (GraphError)."""
        self._doc.save(os.fspath(path))

    # Building and editing: each edit is checked by the loader; a refused edit changes
    # nothing.
    def add_node(self, node_id, type, params=None):
        d = self.to_dict()
        if node_id in d["nodes"]:
            raise GraphError(f"a node '{node_id}' already exists")
        d["nodes"][node_id] = {"type": type, "params": {k: _plain(v) for k, v in (params or {}).items()}}
        self._replace(d)
        return self[node_id]

    def remove_node(self, node_id):
        d = self.to_dict()
        if d["nodes"].pop(node_id, None) is None:
            raise GraphError(f"no node '{node_id}'")
        self._replace(d)

    def connect(self, source, target):
        """Wires output `source` ("node.port") into input `target` ("node.port"); the port
        types must match."""
        _split(source, "source")
        node, port = _split(target, "target")
        d = self.to_dict()
        if node not in d["nodes"]:
            raise GraphError(f"no node '{node}'")
        d["nodes"][node].setdefault("inputs", {})[port] = source
        self._replace(d)

    def disconnect(self, target):
        node, port = _split(target, "target")
        d = self.to_dict()
        if d["nodes"].get(node, {}).get("inputs", {}).pop(port, None) is None:
            raise GraphError(f"input '{target}' is not connected")
        self._replace(d)

    def __getitem__(self, node_id):
        if node_id not in self.to_dict()["nodes"]:
            raise KeyError(node_id)
        return Node(self, node_id)

    def __contains__(self, node_id):
        return node_id in self.to_dict()["nodes"]

    @property
    def nodes(self):
        return [Node(self, n) for n in self.to_dict()["nodes"]]

    @property
    def frames(self):
        """The animation's frames, first and last inclusive."""
        return range(self._doc.first_frame, self._doc.last_frame + 1)

    # Cooking.
    def cook(self, output, frame=None, cache=None, out="out"):
        """Cooks output "node.port" at `frame` (default: the first) and returns its value:
        a float, int or str; a NumPy array for images (height, width, RGBA) and float arrays;
        a Map2D or CloudParticles; a fog volume as a pyopenvdb.FloatGrid when pyopenvdb
        can be imported, else as a FogVolume (to_dense(), to_vdb(path)). `cache` is a disk cache directory shared with the CLI;
        writer nodes write under `out`. Cooking again reuses every output whose key did not
        change; last_report() says what cooked and why. The GIL is released while the engine
        cooks; cancel() from another thread, or Ctrl-C, stops it with nothing partial
        cached."""
        node, port = _split(output, "output")
        first, last = self._doc.first_frame, self._doc.last_frame
        if frame is None:
            frame = first
        elif isinstance(frame, bool) or not hasattr(type(frame), "__index__"):
            # int() would truncate 1.5 to frame 1 and read "3" as 3 without a word.
            raise TypeError(f"frame must be an integer, not {frame!r}")
        frame = operator.index(frame)
        if not first <= frame <= last:
            raise ValueError(f"frame {frame} is outside the graph's frames {first}:{last}")
        value = self._doc.cook(node, port, frame, os.fspath(cache) if cache else "",
                               os.fspath(out))
        return _with_pyopenvdb(value) if isinstance(value, _cloudgraph.FogVolume) else value

    def cancel(self):
        """Cancels the cook under way (from another thread); it raises Cancelled."""
        self._doc.cancel()

    def last_report(self):
        """The last cook's report, as `cloudgraph run --report` writes it: a record per node
        and frame (status cooked / memory / disk, the reason it cooked, seconds)."""
        return json.loads(self._doc.last_report())

    # Internal helpers for Node and Params.
    def _replace(self, d):
        _checked(lambda: self._doc.replace(_dumps(d, self._doc.name)), lambda: d, self._types)

    def _node_dict(self, node_id):
        return self.to_dict()["nodes"][node_id]

    def _type_of(self, node_id):
        return self._types[self._node_dict(node_id)["type"]]

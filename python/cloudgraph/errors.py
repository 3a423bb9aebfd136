"""The exceptions of cloudgraph. Each has `where` (the file and JSON pointer, as the CLI's
messages give it, or "") and `node` (the node id, or None)."""


class Error(Exception):
    """Any CloudGraph error."""

    where = ""
    node = None


class GraphError(Error, ValueError):
    """A bad graph: unknown node type, bad wiring, a cycle, malformed JSON."""


class ParameterError(GraphError):
    """A parameter value of the wrong type, out of range, or not one of its choices."""


class FileError(Error, OSError):
    """A file that cannot be read: the graph file, or an input file a parameter names."""


class CookError(Error, RuntimeError):
    """A node failed while it cooked. `input_fault` is True when its input was at fault (the
    CLI exits 2 then), False for an internal failure (exit 1)."""

    input_fault = False


class Cancelled(Error):
    """The cook was cancelled (Graph.cancel() or Ctrl-C); nothing partial was cached."""

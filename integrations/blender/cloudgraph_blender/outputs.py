"""Where a run's files are: the graph names what its writers wrote under the run's folder."""

import json
import os
import re

# The writers' default file names (their 'file' parameter when a graph leaves it out).
DEFAULT_FILES = {"WriteVDB": "density.####.vdb", "WriteShot": "shot.json"}


class OutputError(Exception):
    """A run's folder or graph that does not hold what the import needs."""


def writer_files(graph_path, node_type):
    """The 'file' of every node of `node_type` in the graph, in the order of their ids."""
    try:
        with open(graph_path, encoding="utf-8") as f:
            graph = json.load(f)
    except (OSError, ValueError) as e:
        raise OutputError("cannot read the graph %s: %s" % (graph_path, e)) from e
    nodes = graph.get("nodes") if isinstance(graph, dict) else None
    if not isinstance(nodes, dict):
        raise OutputError("%s has no 'nodes' object" % graph_path)
    files = []
    for node_id in sorted(nodes):
        node = nodes[node_id]
        if isinstance(node, dict) and node.get("type") == node_type:
            params = node.get("params") or {}
            files.append((node_id, params.get("file", DEFAULT_FILES[node_type])))
    return files


def one_writer(graph_path, node_type):
    """The file of the graph's one `node_type` node."""
    files = writer_files(graph_path, node_type)
    if len(files) != 1:
        raise OutputError("%s has %d %s nodes; the import needs exactly one"
                          % (graph_path, len(files), node_type))
    return files[0]


def vdb_sequence(directory, pattern):
    """The files `pattern` ('####' = the frame) names in `directory`, as (frame, path) in
    frame order; consecutive numbers, as Blender plays a sequence only then."""
    folder = os.path.join(directory, os.path.dirname(pattern))
    name = os.path.basename(pattern)
    if "####" not in name:
        raise OutputError("WriteVDB's file %s has no #### for the frame" % pattern)
    head, tail = name.split("####", 1)
    match = re.compile(re.escape(head) + r"(\d{4,})" + re.escape(tail) + "$")
    try:
        names = os.listdir(folder)
    except OSError as e:
        raise OutputError("no folder %s: %s" % (folder, e)) from e
    found = sorted((int(m.group(1)), os.path.join(folder, n))
                   for n in names for m in [match.match(n)] if m)
    if not found:
        raise OutputError("no VDB files %s in %s" % (name, folder))
    frames = [f for f, _ in found]
    if frames != list(range(frames[0], frames[0] + len(frames))):
        raise OutputError("the VDB frames %s are not consecutive: run the graph with the "
                          "WriteVDB's every = 1" % frames)
    return found


def read_shot(directory, relative):
    """WriteShot's JSON (version 1)."""
    path = os.path.join(directory, relative)
    try:
        with open(path, encoding="utf-8") as f:
            shot = json.load(f)
    except (OSError, ValueError) as e:
        raise OutputError("cannot read the shot %s: %s" % (path, e)) from e
    if shot.get("cloudgraph_shot") != 1:
        raise OutputError("%s is not a CloudGraph shot of version 1" % path)
    return shot

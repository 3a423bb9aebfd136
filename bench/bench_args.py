"""What the bench scripts that run figure graphs take from their command line."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def build_and_graphs(argv=None):
    """(build directory, graph paths) from `BUILD_DIR [GRAPH ...]`; by default build/ and every
    graphs/figure*.json."""
    argv = sys.argv if argv is None else argv
    build = argv[1] if len(argv) > 1 else os.path.join(ROOT, "build")
    graphs = argv[2:] or sorted(
        os.path.join(ROOT, "graphs", f) for f in os.listdir(os.path.join(ROOT, "graphs"))
        if f.startswith("figure") and f.endswith(".json"))
    return build, graphs

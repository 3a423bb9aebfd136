"""Node types written in Python: declared once, cooked in keys, caches and reports like any
node, from Python and from JSON graphs the CLI runs with --python-nodes."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import cloudgraph
from conftest import statuses

SCALE_MODULE = '''
import numpy as np
import cloudgraph

@cloudgraph.node
class {name}:
    """Multiplies a float array by a gain."""
    inputs = {{"values": cloudgraph.Input("FloatArray", "values")}}
    outputs = {{"values": cloudgraph.Output("FloatArray", "values times the gain")}}
    params = {{"gain": cloudgraph.Param(float, 2.0, min=0, max=100, doc="the gain")}}

    def cook(self, inputs, params, context):
        return {{"values": inputs["values"] * np.float32(params["gain"])}}
'''


def array_graph(node_type, gain=2.0):
    """RandomField -> the Python node -> Statistics."""
    return cloudgraph.Graph.from_dict({
        "cloudgraph": 1, "frames": {"start": 0, "end": 0},
        "nodes": {
            "field": {"type": "RandomField", "params": {"width": 16, "height": 8, "seed": 5}},
            "scale": {"type": node_type, "inputs": {"values": "field.values"},
                      "params": {"gain": gain}},
            "stats": {"type": "Statistics", "inputs": {"values": "scale.values"}},
        }})


def register(tmp_path, name, source=SCALE_MODULE):
    """Writes a module of node `name` and runs it as the CLI's --python-nodes does."""
    path = tmp_path / f"{name.lower()}_nodes.py"
    path.write_text(textwrap.dedent(source.format(name=name)))
    return cloudgraph.nodes.load_file(path)


def test_a_python_node_cooks_with_its_declared_parameters(tmp_path):
    register(tmp_path, "ScaleA")
    declared = cloudgraph.node_types()["ScaleA"]
    assert declared.params["gain"].default == 2.0 and declared.params["gain"].max == 100
    assert [p.type for p in declared.inputs] == ["FloatArray"]
    g = array_graph("ScaleA", gain=3.0)
    field = g.cook("field.values")
    assert np.array_equal(g.cook("scale.values"), field * np.float32(3.0))
    with pytest.raises(cloudgraph.ParameterError) as error:
        g["scale"].params["gain"] = 101
    assert error.value.node == "scale"


def test_a_python_node_is_keyed_and_cached_like_any_node(tmp_path):
    register(tmp_path, "ScaleB")
    g = array_graph("ScaleB")
    g.cook("stats.mean", cache=tmp_path / "cache")
    assert statuses(g.last_report(), 0)["scale"] == "cooked"
    g.cook("stats.mean", cache=tmp_path / "cache")
    assert statuses(g.last_report(), 0)["scale"] == "memory-hit"
    g["scale"].params["gain"] = 4.0
    g.cook("stats.mean", cache=tmp_path / "cache")
    assert {n: s for n, s in statuses(g.last_report(), 0).items() if s == "cooked"} == \
        {"scale": "cooked", "stats": "cooked"}
    # Another graph, the same content: from the disk cache.
    other = array_graph("ScaleB", gain=4.0)
    other.cook("stats.mean", cache=tmp_path / "cache")
    assert statuses(other.last_report(), 0)["scale"] == "disk-hit"


def test_a_python_node_inside_a_json_graph_run_by_the_cli(tmp_path, cli):
    nodes = Path(register(tmp_path, "ScaleC").__file__)
    g = array_graph("ScaleC", gain=0.5)
    g.add_node("text", "WriteText", {"file": "mean.txt"})
    g.connect("stats.summary", "text.text")
    g.save(tmp_path / "graph.json")
    run = [cli, "run", str(tmp_path / "graph.json"), "--python-nodes", str(nodes), "-q",
           "--cache", str(tmp_path / "cache"), "--report", str(tmp_path / "report.json")]
    subprocess.run(run + ["--out", str(tmp_path / "cli")], check=True)
    g.cook("text.files", out=tmp_path / "py")
    assert (tmp_path / "cli" / "mean.txt").read_bytes() == (tmp_path / "py" / "mean.txt").read_bytes()
    report = json.loads((tmp_path / "report.json").read_text())
    assert statuses(report, 0)["scale"] == "cooked"
    # The same code and content again: a cache hit. An edit to the module re-keys the node.
    # (Each run writes to a new folder, so that its writer, and what it reads, cook.)
    subprocess.run(run + ["--out", str(tmp_path / "cli2")], check=True)
    assert statuses(json.loads((tmp_path / "report.json").read_text()), 0)["scale"] == "disk-hit"
    nodes.write_text(nodes.read_text() + "\n# an edit\n")
    subprocess.run(run + ["--out", str(tmp_path / "cli3")], check=True)
    report = json.loads((tmp_path / "report.json").read_text())
    assert statuses(report, 0)["scale"] == "cooked"
    assert statuses(report, 0)["field"] == "disk-hit"


def test_the_cli_refuses_a_python_file_it_cannot_run(tmp_path, cli):
    broken = tmp_path / "broken.py"
    broken.write_text("import cloudgraph\ndef (:\n")
    result = subprocess.run([cli, "nodes", "--python-nodes", str(broken)], capture_output=True,
                            text=True)
    assert result.returncode == 2
    assert str(broken) in result.stderr and "SyntaxError" in result.stderr


RAISING_MODULE = '''
import cloudgraph

@cloudgraph.node
class {name}:
    """Fails while `failing` is set."""
    failing = True
    inputs = {{"values": cloudgraph.Input("FloatArray", "values")}}
    outputs = {{"values": cloudgraph.Output("FloatArray", "the same values")}}
    params = {{"gain": cloudgraph.Param(float, 2.0, doc="unused")}}

    def cook(self, inputs, params, context):
        if {name}.failing:
            explode()
        return {{"values": inputs["values"]}}

def explode():
    raise ValueError("the node failed on purpose")
'''


def test_a_raising_python_node_names_itself_and_its_traceback_and_caches_nothing(tmp_path):
    module = register(tmp_path, "RaiseD", RAISING_MODULE)
    g = array_graph("RaiseD")
    with pytest.raises(cloudgraph.CookError) as error:
        g.cook("stats.mean", cache=tmp_path / "cache")
    assert error.value.node == "scale"
    assert "ValueError: the node failed on purpose" in str(error.value)
    assert "in explode" in str(error.value)  # the traceback, down to the raising function
    module.RaiseD.failing = False
    g.cook("stats.mean", cache=tmp_path / "cache")
    assert statuses(g.last_report(), 0)["scale"] == "cooked"  # nothing was cached before


def test_bad_returns_and_undeclared_reads_are_cook_errors(tmp_path):
    @cloudgraph.node
    class WrongOutputE:
        """Returns a string where an array is declared."""
        inputs = {"values": cloudgraph.Input("FloatArray", "values")}
        outputs = {"values": cloudgraph.Output("FloatArray", "values")}
        params = {"gain": cloudgraph.Param(float, 1.0, doc="unused")}

        def cook(self, inputs, params, context):
            return {"values": "not an array"}

    @cloudgraph.node
    class ReadsFrameE:
        """Reads the frame without declaring frame_dependent."""
        inputs = {"values": cloudgraph.Input("FloatArray", "values")}
        outputs = {"values": cloudgraph.Output("FloatArray", "values")}
        params = {"gain": cloudgraph.Param(float, 1.0, doc="unused")}

        def cook(self, inputs, params, context):
            return {"values": inputs["values"] + context.frame}

    with pytest.raises(cloudgraph.CookError, match="output 'values' \\(FloatArray\\)"):
        array_graph("WrongOutputE").cook("scale.values")
    with pytest.raises(cloudgraph.CookError, match="frame_dependent = True"):
        array_graph("ReadsFrameE").cook("scale.values")


def test_a_taken_type_name_is_refused_unless_it_is_the_same_node(tmp_path):
    module = register(tmp_path, "ScaleF")
    cloudgraph.nodes.load_file(module.__file__)  # the same module again: allowed
    with pytest.raises(cloudgraph.GraphError, match="already registered"):
        @cloudgraph.node
        class Renderer:
            """Not the Renderer."""
            outputs = {"x": cloudgraph.Output("Float", "x")}

            def cook(self, inputs, params, context):
                return {"x": 1.0}


def test_a_declaration_the_engine_cannot_take_is_refused():
    with pytest.raises(cloudgraph.ParameterError, match="must be a string"):
        @cloudgraph.node
        class FileNumberH:
            """An input file that is not a name."""
            outputs = {"x": cloudgraph.Output("Float", "x")}
            params = {"file": cloudgraph.Param(float, 1.0, role="input_file", doc="a file")}

            def cook(self, inputs, params, context):
                return {"x": 1.0}
    with pytest.raises(cloudgraph.GraphError, match="Imag"):
        @cloudgraph.node
        class TypoH:
            """A port of an unknown type."""
            outputs = {"x": cloudgraph.Output("Imag", "x")}

            def cook(self, inputs, params, context):
                return {"x": 1.0}
    assert "FileNumberH" not in cloudgraph.node_types() and "TypoH" not in cloudgraph.node_types()


def test_an_input_file_s_content_keys_the_node(tmp_path):
    @cloudgraph.node
    class ReadNumberG:
        """Reads one number from a text file."""
        outputs = {"value": cloudgraph.Output("Float", "the number")}
        params = {"file": cloudgraph.Param(str, "number.txt", role="input_file",
                                           doc="a text file holding a number")}

        def cook(self, inputs, params, context):
            with open(params["file"]) as f:
                return {"value": float(f.read())}

    (tmp_path / "a.txt").write_text("1.5")
    (tmp_path / "b.txt").write_text("1.5")
    g = cloudgraph.Graph.from_dict({"cloudgraph": 1, "frames": {"start": 0, "end": 0},
                                    "nodes": {"read": {"type": "ReadNumberG",
                                                       "params": {"file": "a.txt"}}}},
                                   base_dir=tmp_path)
    assert g.cook("read.value", cache=tmp_path / "cache") == 1.5
    g["read"].params["file"] = str(tmp_path / "b.txt")  # another name, the same content
    assert g.cook("read.value", cache=tmp_path / "cache") == 1.5
    assert statuses(g.last_report(), 0)["read"] == "memory-hit"
    (tmp_path / "b.txt").write_text("2.5")
    assert g.cook("read.value", cache=tmp_path / "cache") == 2.5


def test_an_output_out_of_its_type_s_range_names_the_node_and_output():
    @cloudgraph.node
    class HugeI:
        """Returns numbers no Int or Float holds."""
        outputs = {"count": cloudgraph.Output("Int", "a count"),
                   "size": cloudgraph.Output("Float", "a size")}
        params = {"huge": cloudgraph.Param(str, "count", choices=["count", "size"], doc="which")}

        def cook(self, inputs, params, context):
            big = 2**64 if params["huge"] == "count" else 10**400
            return {"count": big if params["huge"] == "count" else 1,
                    "size": float(big) if params["huge"] == "count" else big}

    g = cloudgraph.Graph.from_dict({"cloudgraph": 1, "frames": {"start": 0, "end": 0},
                                    "nodes": {"huge": {"type": "HugeI"}}})
    for which, output in [("count", "count"), ("size", "size")]:
        g["huge"].params["huge"] = which
        with pytest.raises(cloudgraph.CookError) as error:
            g.cook(f"huge.{output}")
        assert error.value.node == "huge"
        message = str(error.value)
        assert "'huge'" in message and f"output '{output}'" in message
        assert "Unable to cast" not in message


HOSTILE_MODULE = '''
import pathlib
pathlib.Path({marker!r}).joinpath({name!r}).write_text("imported")
'''


@pytest.mark.parametrize("source", ["working directory", "PYTHONPATH", "user site"])
def test_the_cli_s_python_imports_nothing_from_the_working_directory_or_environment(
        tmp_path, cli, source):
    """The embedded interpreter is isolated: a module in the directory the CLI runs from, on
    PYTHONPATH or in the user's site directory neither shadows the standard library (nor
    NumPy) nor runs at start-up."""
    markers, work, home = tmp_path / "markers", tmp_path / "work", tmp_path / "home"
    for folder in markers, work, home:
        folder.mkdir()
    version = f"python{sys.version_info[0]}.{sys.version_info[1]}"
    folder = {"working directory": work, "PYTHONPATH": tmp_path / "path",
              "user site": home / ".local" / "lib" / version / "site-packages"}[source]
    folder.mkdir(parents=True, exist_ok=True)
    for name in ["json", "typing", "hashlib", "inspect", "numpy", "sitecustomize",
                 "usercustomize"]:
        (folder / f"{name}.py").write_text(HOSTILE_MODULE.format(marker=str(markers), name=name))
    (home / "startup.py").write_text(HOSTILE_MODULE.format(marker=str(markers), name="startup"))
    nodes = Path(register(tmp_path, "ScaleJ").__file__)
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env.update(HOME=str(home), PYTHONSTARTUP=str(home / "startup.py"))
    if source == "PYTHONPATH":
        env["PYTHONPATH"] = str(folder)
    result = subprocess.run([cli, "nodes", "ScaleJ", "--python-nodes", str(nodes)], cwd=work,
                            env=env, capture_output=True, text=True)
    assert sorted(p.name for p in markers.iterdir()) == []
    assert result.returncode == 0, result.stderr
    assert "ScaleJ" in result.stdout

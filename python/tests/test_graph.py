"""Loading, editing and saving graphs, node declarations, and errors."""

import json
import subprocess

import numpy as np
import pytest

import cloudgraph
from conftest import FIGURE6


def test_load_gives_the_file_nodes_and_parameters():
    g = cloudgraph.Graph.load(FIGURE6)
    with open(FIGURE6) as f:
        on_disk = json.load(f)
    assert sorted(n.id for n in g.nodes) == sorted(on_disk["nodes"])
    assert g.frames == range(on_disk["frames"]["start"], on_disk["frames"]["end"] + 1)
    for node_id, node in on_disk["nodes"].items():
        assert g[node_id].type == node["type"]
        for name, value in node.get("params", {}).items():
            assert g[node_id].params[name] == value


def test_dict_round_trip_is_exact():
    g = cloudgraph.Graph.load(FIGURE6)
    again = cloudgraph.Graph.from_dict(g.to_dict())
    assert again.to_dict() == g.to_dict()


def test_unset_parameters_read_their_declared_default():
    g = cloudgraph.Graph.load(FIGURE6)
    declared = cloudgraph.node_types()["Renderer"].params
    for name, param in declared.items():
        if name not in g.to_dict()["nodes"]["render"].get("params", {}):
            assert g["render"].params[name] == param.default


def test_node_types_carry_ports_parameters_units_and_docs():
    types = cloudgraph.node_types()
    voxelizer = types["Voxelizer"]
    assert [p.name for p in voxelizer.inputs] == ["particles", "condensation", "atmosphere"]
    assert voxelizer.inputs[0].type == "CloudParticles"
    assert [p.name for p in voxelizer.outputs] == ["volume"]
    size = voxelizer.params["voxelSize"]
    assert size.units == "m" and size.min is not None and size.default > 0 and size.doc
    assert "gaussian" in voxelizer.params["kernel"].choices


def test_a_parameter_is_checked_when_assigned(small_figure6):
    render = small_figure6["render"]
    render.params["sunDirection"] = [1, 0, 0.5]
    assert render.params["sunDirection"] == [1, 0, 0.5]
    with pytest.raises(cloudgraph.ParameterError) as error:
        render.params["width"] = -3
    assert error.value.node == "render"
    assert error.value.where.endswith(":/nodes/render/params/width")
    assert "minimum" in str(error.value)
    assert render.params["width"] == 96  # a refused value changes nothing
    with pytest.raises(cloudgraph.ParameterError):
        render.params["sunDirection"] = "up"
    with pytest.raises(cloudgraph.ParameterError) as error:
        small_figure6["voxelize"].params["kernel"] = "boxy"
    assert error.value.node == "voxelize"


def test_build_a_graph_node_by_node_and_save_it_for_the_cli(tmp_path, cli):
    g = cloudgraph.Graph.from_dict({"cloudgraph": 1, "frames": {"start": 0, "end": 0}, "nodes": {}})
    g.add_node("cloud", "SyntheticCumulus", {"voxelSize": 60.0})
    g.add_node("render", "Renderer", {"width": 32, "height": 24})
    with pytest.raises(cloudgraph.GraphError) as error:
        g.save(tmp_path / "incomplete.json")  # the renderer's volume is not connected yet
    assert error.value.node == "render"
    assert not (tmp_path / "incomplete.json").exists()
    g.connect("cloud.volume", "render.volume")
    g.save(tmp_path / "built.json")
    subprocess.run([cli, "validate", str(tmp_path / "built.json")], check=True)
    assert cloudgraph.Graph.load(tmp_path / "built.json").to_dict() == g.to_dict()


def test_wiring_is_type_checked_and_a_refused_edit_changes_nothing(small_figure6):
    before = small_figure6.to_dict()
    with pytest.raises(cloudgraph.GraphError) as error:
        small_figure6.connect("noise.map", "render.volume")  # a Map2D into a FogVolume
    assert "takes FogVolume" in str(error.value) and error.value.node == "render"
    with pytest.raises(cloudgraph.GraphError):
        small_figure6.add_node("x", "NoSuchNode")
    with pytest.raises(cloudgraph.GraphError):
        small_figure6.remove_node("voxelize")  # the renderer reads it
    assert small_figure6.to_dict() == before


def test_errors_have_their_own_types(tmp_path):
    with pytest.raises(cloudgraph.FileError):
        cloudgraph.Graph.load(tmp_path / "missing.json")
    (tmp_path / "bad.json").write_text('{"cloudgraph": 1, "nodes": {"a": {"type": "Nope"}}}')
    with pytest.raises(cloudgraph.GraphError) as error:
        cloudgraph.Graph.load(tmp_path / "bad.json")
    assert error.value.node == "a" and "bad.json:/nodes/a" in error.value.where
    g = cloudgraph.Graph.from_dict({"cloudgraph": 1, "frames": {"start": 0, "end": 0}, "nodes": {}},
                                   base_dir=tmp_path)
    with pytest.raises(cloudgraph.FileError) as error:
        g.add_node("read", "ReadVDB", {"file": "nowhere.vdb"})
    assert error.value.node == "read"


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf"), np.float32("nan")])
def test_a_non_finite_parameter_is_refused_as_not_finite(small_figure6, bad):
    # A number, and a number inside a vector, assigned; then a new node's parameters.
    for node, name, value, pointer in [
            ("voxelize", "voxelSize", bad, "/nodes/voxelize/params/voxelSize"),
            ("render", "sunDirection", [1, bad, 0.5], "/nodes/render/params/sunDirection/1")]:
        params = small_figure6[node].params
        before = params[name]
        with pytest.raises(cloudgraph.ParameterError, match="is not finite") as error:
            params[name] = value
        assert error.value.node == node
        assert error.value.where.endswith(pointer)
        assert f"(node '{node}')" in str(error.value)
        assert params[name] == before
    with pytest.raises(cloudgraph.ParameterError, match="is not finite") as error:
        small_figure6.add_node("cloud2", "SyntheticCumulus", {"voxelSize": bad})
    assert error.value.node == "cloud2"
    assert error.value.where.endswith("/nodes/cloud2/params/voxelSize")
    assert "cloud2" not in small_figure6
    d = small_figure6.to_dict()
    d["nodes"]["voxelize"]["params"]["voxelSize"] = float(bad)
    with pytest.raises(cloudgraph.ParameterError, match="is not finite") as error:
        cloudgraph.Graph.from_dict(d, name="edited")
    assert error.value.where == "edited:/nodes/voxelize/params/voxelSize"

"""The worked examples of docs/python.md (docs/examples/python/), run as a user runs them, and
what they claim checked."""

import importlib.util
import subprocess
import sys

import numpy as np
import pytest

import cloudgraph
from conftest import FIGURE6, SOURCE, shrink

EXAMPLES = SOURCE / "docs" / "examples" / "python"


def run_example(name, cwd, *args):
    """Runs an example script from a folder that has the repository's graphs/, as a user in
    the repository root would."""
    (cwd / "graphs").symlink_to(SOURCE / "graphs")
    subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], cwd=cwd, check=True)


def import_example(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name", ["contact_sheet.py", "clearing.py", "grade.py"])
def test_the_docs_show_each_example_as_it_is(name):
    assert (EXAMPLES / name).read_text().strip() in (SOURCE / "docs" / "python.md").read_text()


def test_write_image_writes_what_write_image_nodes_write(tmp_path):
    g = cloudgraph.Graph.load(SOURCE / "graphs" / "cumulus_still.json")
    g["render"].params["width"], g["render"].params["height"] = 64, 48
    g.cook("write.files", out=tmp_path / "node")
    cloudgraph.write_image(tmp_path / "py.png", g.cook("render.image"), seed=0)  # seed: the frame
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "node" / "cumulus_still.png").read_bytes()
    image = g.cook("render.image")
    for bad in (dict(path=tmp_path / "x.png", tone_map="filmic"), dict(path=tmp_path / "x.jpg"),
                dict(path=tmp_path / "x.png", image=image[..., 0])):
        with pytest.raises(ValueError):
            cloudgraph.write_image(**{"image": image, **bad})
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "x.jpg").exists()


def test_write_image_through_ocio_writes_what_the_node_writes(tmp_path, monkeypatch):
    monkeypatch.delenv("OCIO", raising=False)  # the built-in config on both sides
    g = cloudgraph.Graph.load(SOURCE / "graphs" / "cumulus_still.json")
    g["render"].params["width"], g["render"].params["height"] = 64, 48
    g["write"].params["toneMap"] = "ocio"
    g.cook("write.files", out=tmp_path / "node")
    cloudgraph.write_image(tmp_path / "py.png", g.cook("render.image"), tone_map="ocio", seed=0)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "node" / "cumulus_still.png").read_bytes()
    # The ACES view is not the fitted curve: the same image through 'aces' differs.
    cloudgraph.write_image(tmp_path / "fit.png", g.cook("render.image"), seed=0)
    assert (tmp_path / "fit.png").read_bytes() != (tmp_path / "py.png").read_bytes()


def test_the_contact_sheet_holds_the_nine_renders(tmp_path):
    run_example("contact_sheet.py", tmp_path)
    # The same nine renders, each cooked from scratch, tiled by hand.
    tiles = []
    for i in range(9):
        g = cloudgraph.Graph.load(SOURCE / "graphs" / "cumulus_still.json")
        g["render"].params["width"], g["render"].params["height"] = 240, 180
        azimuth = 2 * np.pi * i / 9
        g["render"].params["sunDirection"] = [np.cos(azimuth), np.sin(azimuth), 0.6]
        tiles.append(g.cook("render.image"))
    assert all(not np.array_equal(tiles[0], t) for t in tiles[1:])  # the sun moved
    sheet = np.concatenate([np.concatenate(tiles[3 * r:3 * r + 3], axis=1) for r in range(3)])
    assert sheet.shape == (540, 720, 4)
    cloudgraph.write_image(tmp_path / "expected.png", sheet)
    assert (tmp_path / "out" / "sun_wedge.png").read_bytes() == (tmp_path / "expected.png").read_bytes()


def test_the_clearing_keeps_clouds_out_of_its_disc(tmp_path, small_figure6_file):
    run_example("clearing.py", tmp_path, small_figure6_file)
    assert (tmp_path / "out" / "clearing.png").stat().st_size > 0
    clearing = import_example("clearing")
    radius, frame = 1000.0, 400
    cleared = clearing.with_clearing(shrink(cloudgraph.Graph.load(FIGURE6)), radius)
    noise = cleared.cook("noise.map").values
    edited = cleared.cook("clearing.map")
    ny, nx = noise.shape
    y, x = (np.mgrid[0:ny, 0:nx] + 0.5) * edited.cell_size
    centre = nx * edited.cell_size / 2, ny * edited.cell_size / 2
    inside = np.hypot(x - centre[0], y - centre[1]) < radius
    assert inside.any() and noise[inside].max() > 0
    assert np.all(edited.values[inside] == 0)
    assert np.array_equal(edited.values[~inside], noise[~inside])
    # No vapour rose in the disc, so no cloud copy stands in it; without it, clouds do.
    def distances(graph):
        origins = graph.cook("cloud.particles", frame, cache=tmp_path / "out" / "cache").copy_origins
        return np.hypot(origins[:, 0] - centre[0], origins[:, 1] - centre[1])
    with_disc = distances(cleared)
    without = distances(shrink(cloudgraph.Graph.load(FIGURE6)))
    assert len(with_disc) > 0 and with_disc.min() > 0.9 * radius
    assert (without < radius / 2).sum() >= 3


def test_the_grade_node_in_a_json_graph(tmp_path, cli):
    graph = EXAMPLES / "graded_cumulus.json"
    subprocess.run([cli, "run", str(graph), "--python-nodes", str(EXAMPLES / "grade.py"),
                    "--out", str(tmp_path / "cli"), "-q"], check=True)
    import_example("grade")  # registers Grade in this process
    g = cloudgraph.Graph.load(graph)
    g.cook("write.files", out=tmp_path / "py")
    assert (tmp_path / "cli" / "graded_cumulus.png").read_bytes() == \
        (tmp_path / "py" / "graded_cumulus.png").read_bytes()
    # The grade itself: 2^exposure, then saturation about the Rec. 709 luminance.
    render, graded = g.cook("render.image"), g.cook("grade.image")
    rgb = render[..., :3].astype(np.float64) * 2 ** 0.5
    luminance = rgb @ [0.2126, 0.7152, 0.0722]
    expected = luminance[..., None] + 0.8 * (rgb - luminance[..., None])
    np.testing.assert_allclose(graded[..., :3], expected, rtol=1e-5, atol=1e-6)
    assert np.array_equal(graded[..., 3], render[..., 3])

"""Cooking from Python: the same values as the CLI, the same caches, reports, cancelling."""

import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import cloudgraph
from conftest import shrink, statuses

FRAME = 150


def test_cooked_image_equals_the_cli_s_bit_for_bit(tmp_path, small_figure6, small_figure6_file, cli):
    # The CLI cooks the frame into a disk cache; the same graph cooked from Python with that
    # cache reads the CLI's render back, and without it cooks its own: the two are equal.
    cache = tmp_path / "cache"
    subprocess.run([cli, "run", str(small_figure6_file), "--frames", f"{FRAME}:{FRAME}", "--cache",
                    str(cache), "--out", str(tmp_path / "cli"), "-q"], check=True)
    reader = cloudgraph.Graph.load(small_figure6_file)
    from_cli = reader.cook("render.image", FRAME, cache=cache)
    assert statuses(reader.last_report(), FRAME)["render"] == "disk-hit"
    own = small_figure6.cook("render.image", FRAME, out=tmp_path / "py")
    assert statuses(small_figure6.last_report(), FRAME)["render"] == "cooked"
    assert own.shape == (64, 96, 4) and own.dtype == np.float32
    assert not own.flags.writeable
    assert own[..., 3].max() > 0.1  # the cloud is in the picture
    assert own.tobytes() == from_cli.tobytes()


def test_the_writers_write_the_cli_s_bytes(tmp_path, small_figure6_file, cli):
    subprocess.run([cli, "run", str(small_figure6_file), "--frames", f"{FRAME}:{FRAME}",
                    "--out", str(tmp_path / "cli"), "-q"], check=True)
    g = cloudgraph.Graph.load(small_figure6_file)
    for writer in ("image", "vdb"):
        if writer not in g:
            continue
        port = cloudgraph.node_types()[g[writer].type].outputs[0].name
        g.cook(f"{writer}.{port}", FRAME, out=tmp_path / "py")
    written = sorted(p.relative_to(tmp_path / "py") for p in (tmp_path / "py").rglob("*") if p.is_file())
    assert written
    for name in written:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_values_come_as_numpy(small_figure6):
    noise = small_figure6.cook("noise.map")
    assert noise.values.shape == (small_figure6["noise"].params["height"], small_figure6["noise"].params["width"])
    assert noise.cell_size == small_figure6["noise"].params["cellSize"]
    assert np.asarray(noise).dtype == np.float32
    particles = small_figure6.cook("cloud.particles", FRAME)
    assert particles.positions.shape == (len(particles), 3) and len(particles) > 0
    assert set(np.unique(particles.levels)) <= set(range(1, 6))


def test_a_fog_volume_without_pyopenvdb(monkeypatch, tmp_path, small_figure6):
    monkeypatch.setitem(sys.modules, "pyopenvdb", None)  # as if it were not installed
    volume = small_figure6.cook("voxelize.volume", FRAME)
    assert isinstance(volume, cloudgraph.FogVolume)
    assert volume.voxel_size == small_figure6["voxelize"].params["voxelSize"]
    dense, origin = volume.to_dense()
    assert np.count_nonzero(dense) == volume.active_voxel_count > 0
    # Figure 6 holds the cloud's water: values are (LWC / 1 g m^-3)^(2/3), above 1 where a
    # cloud holds more than 1 g/m^3 but far below 10 (1000 g/m^3 of liquid water).
    assert 0.0 < dense.max() < 10.0
    low, high = volume.bbox
    assert tuple(origin) == tuple(low) and dense.shape == tuple(h - l + 1 for l, h in zip(low, high))


def test_a_fog_volume_as_a_pyopenvdb_grid_equals_the_cli_s_vdb(tmp_path, small_figure6, cli):
    pyopenvdb = pytest.importorskip("pyopenvdb")  # scripts/install-deps.sh --tests installs it
    small_figure6["vdb"].params["every"] = 1  # every frame, full floats
    small_figure6["vdb"].params["halfFloat"] = False
    small_figure6.save(tmp_path / "graph.json")
    subprocess.run([cli, "run", str(tmp_path / "graph.json"), "--frames", f"{FRAME}:{FRAME}",
                    "--out", str(tmp_path / "cli"), "-q"], check=True)
    grid = small_figure6.cook("voxelize.volume", FRAME)
    assert isinstance(grid, pyopenvdb.FloatGrid) and grid.name == "density"
    [written] = (tmp_path / "cli").rglob("*.vdb")
    reference = pyopenvdb.read(str(written), "density")
    assert grid.activeVoxelCount() == reference.activeVoxelCount() > 0
    assert grid.evalActiveVoxelBoundingBox() == reference.evalActiveVoxelBoundingBox()
    low, high = grid.evalActiveVoxelBoundingBox()
    shape = tuple(h - l + 1 for l, h in zip(low, high))
    ours, theirs = np.zeros(shape, np.float32), np.zeros(shape, np.float32)
    grid.copyToArray(ours, ijk=low)
    reference.copyToArray(theirs, ijk=low)
    assert np.array_equal(ours, theirs)


def test_a_wedge_recooks_only_what_the_parameter_feeds(tmp_path, small_figure6):
    cache = tmp_path / "cache"
    images = []
    for i, height in enumerate([0.1, 0.3, 0.5, 0.7, 0.9]):
        small_figure6["render"].params["sunDirection"] = [1.0, 0.3, height]
        images.append(small_figure6.cook("render.image", FRAME, cache=cache))
        cooked = {n for n, s in statuses(small_figure6.last_report(), FRAME).items() if s == "cooked"}
        if i == 0:
            assert {"primitive", "mapper", "voxelize", "render"} <= cooked
        else:
            assert cooked == {"render"}
    assert len({im.tobytes() for im in images}) == 5
    # A second process, a graph loaded afresh: everything comes from the shared disk cache.
    again = cloudgraph.Graph.from_dict(small_figure6.to_dict())
    again.cook("render.image", FRAME, cache=cache)
    report = statuses(again.last_report(), FRAME)
    assert "cloud" not in report  # the particle stream behind the cached Voxelizer: not made
    assert set(report.values()) == {"disk-hit"}


def test_a_cancelled_cook_caches_nothing_partial(tmp_path, small_figure6):
    # A large render of a grown cloud (about a second here), so the cancel lands in it.
    frame = 300
    small_figure6["render"].params["width"] = 3600
    small_figure6["render"].params["height"] = 2400
    cache = tmp_path / "cache"
    small_figure6.cook("voxelize.volume", frame, cache=cache)
    errors = []

    def cook():
        try:
            small_figure6.cook("render.image", frame, cache=cache)
        except cloudgraph.Cancelled as e:
            errors.append(e)

    worker = threading.Thread(target=cook)
    started = time.monotonic()
    worker.start()
    time.sleep(0.2)
    small_figure6.cancel()
    worker.join()
    assert errors, "the cook ended before it was cancelled"
    assert time.monotonic() - started < 10
    assert "render" not in statuses(small_figure6.last_report(), frame)
    fresh = cloudgraph.Graph.from_dict(small_figure6.to_dict())
    image = fresh.cook("render.image", frame, cache=cache)
    report = statuses(fresh.last_report(), frame)
    assert report["render"] == "cooked" and report["voxelize"] == "disk-hit"
    assert image[..., 3].max() > 0.1


def test_a_bad_input_file_raises_file_error_with_the_node_id(tmp_path):
    (tmp_path / "broken.vdb").write_bytes(b"not a vdb file at all" * 10)
    g = cloudgraph.Graph.from_dict({"cloudgraph": 1, "frames": {"start": 0, "end": 0}, "nodes": {
        "cloud": {"type": "SyntheticCumulus"}}}, base_dir=tmp_path)
    g.add_node("read", "ReadVDB")
    with pytest.raises(cloudgraph.FileError) as error:  # its header is read when it is set
        g["read"].params["file"] = "broken.vdb"
    assert error.value.node == "read"
    assert "broken.vdb" in str(error.value)


def test_cook_refuses_a_fractional_or_out_of_range_frame(small_figure6):
    frames = small_figure6.frames
    for frame in (1.5, 2.0, "3", True):
        with pytest.raises(TypeError, match="frame"):
            small_figure6.cook("noise.map", frame=frame)
    for frame in (frames.start - 1, frames.stop, 2**32 + frames.start, 2**63, -2**70):
        with pytest.raises(ValueError, match="frame") as error:
            small_figure6.cook("noise.map", frame=frame)
        assert f"{frames.start}:{frames.stop - 1}" in str(error.value)
    # NumPy integers are integers; the last frame is in the range.
    small_figure6.cook("noise.map", frame=np.int64(frames.start))
    small_figure6.cook("noise.map", frame=frames.stop - 1)

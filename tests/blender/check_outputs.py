# The user guide's Blender steps (docs/user-guide.md, "Opening the outputs"), headless:
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/check_outputs.py -- \
#       --cloudgraph build/cli/cloudgraph --graph tests/blender/cloud.json --work /tmp/bl
# runs the graph with the CLI, then imports its VDB sequence and PLY files as the guide says
# and checks what Blender makes of them. Any failed check exits 1.

import argparse
import json
import os
import re
import shutil
import subprocess
import sys

import bpy
import mathutils


def fail(message):
    raise SystemExit("check_outputs: " + message)


def check(condition, message):
    if not condition:
        fail(message)


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(description="check CloudGraph outputs in Blender")
    p.add_argument("--cloudgraph", required=True, help="the cloudgraph binary")
    p.add_argument("--graph", required=True, help="graph writing blender/density.####.vdb etc.")
    p.add_argument("--work", required=True, help="scratch directory (emptied first)")
    return p.parse_args(argv)


def run_graph(args):
    shutil.rmtree(args.work, ignore_errors=True)
    out = os.path.join(args.work, "out")
    report = os.path.join(args.work, "report.json")
    subprocess.run([args.cloudgraph, "run", args.graph, "--out", out, "--report", report, "-q"],
                   check=True)
    with open(report) as f:
        records = json.load(f)["records"]
    # Condensation's firstFrame on the last frame: where the cloud forms.
    first = [r["values"]["firstFrame"] for r in records if r["node"] == "condense"][-1]
    return os.path.join(out, "blender"), first


def evaluated(obj, frame):
    bpy.context.scene.frame_set(frame)
    return obj.evaluated_get(bpy.context.evaluated_depsgraph_get())


def bounds(obj):
    """World-space (min, max) corners of an evaluated object's bounding box."""
    corners = [obj.matrix_world @ mathutils.Vector(c) for c in obj.bound_box]
    return ([min(c[i] for c in corners) for i in range(3)],
            [max(c[i] for c in corners) for i in range(3)])


def check_vdb_sequence(folder, cloud_frame):
    """Add > Volume > Import OpenVDB, all files of the sequence selected (A in the browser)."""
    names = sorted(n for n in os.listdir(folder) if re.fullmatch(r"density\.\d{4}\.vdb", n))
    numbers = [int(n[8:12]) for n in names]
    check(len(names) > 1, "expected a VDB sequence, got %s" % names)
    check(numbers[0] == cloud_frame,
          "the first VDB is frame %d, the cloud forms at frame %d" % (numbers[0], cloud_frame))
    check(numbers == list(range(numbers[0], numbers[0] + len(numbers))),
          "VDB numbers are not consecutive: %s" % numbers)
    result = bpy.ops.object.volume_import(filepath=os.path.join(folder, names[0]), directory=folder,
                                          files=[{"name": n} for n in names])
    check(result == {"FINISHED"}, "volume_import: %s" % result)
    obj = bpy.context.active_object
    volume = obj.data
    check(obj.type == "VOLUME", "imported a %s, not a volume" % obj.type)
    check(volume.is_sequence and volume.frame_duration == len(names),
          "Blender sees no sequence of %d frames (is_sequence %s, frame_duration %d)"
          % (len(names), volume.is_sequence, volume.frame_duration))
    # The guide: set Start to the first file's number, and Blender's frames are ours.
    volume.frame_start = numbers[0]
    for frame in (numbers[0], numbers[-1]):
        ev = evaluated(obj, frame)
        grids = ev.data.grids
        check(grids.is_loaded, "frame %d: grids not loaded: %s" % (frame, grids.error_message))
        check(os.path.basename(grids.frame_filepath) == "density.%04d.vdb" % frame,
              "Blender frame %d shows %s" % (frame, grids.frame_filepath))
        density = grids.get("density")
        check(density is not None and density.data_type == "FLOAT",
              "frame %d: no float grid 'density' in %s" % (frame, [g.name for g in grids]))
        lo, hi = bounds(ev)
        check(all(h - l > 0 for l, h in zip(lo, hi)),
              "frame %d: empty bounds %s %s" % (frame, lo, hi))
    # Before the sequence (mode Clip) Blender shows nothing.
    check(not evaluated(obj, numbers[0] - 1).data.grids.is_loaded, "a grid before the sequence")
    return obj, numbers


def ply_header(path):
    """The vertex count and property names in a PLY header."""
    with open(path, "rb") as f:
        header = f.read(4096).split(b"end_header")[0].decode("ascii")
    count = int(re.search(r"element vertex (\d+)", header).group(1))
    return count, re.findall(r"property \w+ (\w+)", header)


def check_ply(path):
    """File > Import > Stanford PLY: every point comes in; properties but x y z do not."""
    count, properties = ply_header(path)
    check(count > 0, "%s has no points" % path)
    result = bpy.ops.import_mesh.ply(filepath=path)
    check(result == {"FINISHED"}, "import_mesh.ply: %s" % result)
    mesh = bpy.context.active_object.data
    check(len(mesh.vertices) == count, "%s: %d vertices in Blender, %d in the file"
          % (path, len(mesh.vertices), count))
    # The guide says Blender drops our custom properties: still true?
    kept = [p for p in properties if p not in ("x", "y", "z") and p in mesh.attributes]
    check(not kept, "Blender now keeps PLY properties %s: update docs/user-guide.md" % kept)
    return bpy.context.active_object


def check_render(obj, frame, work):
    """F12 with Cycles: the volume, with no material of ours, renders as cloud."""
    scene = bpy.context.scene
    ev = evaluated(obj, frame)
    lo, hi = bounds(ev)
    centre = mathutils.Vector([(l + h) / 2 for l, h in zip(lo, hi)])
    camera = scene.camera
    camera.location = centre + mathutils.Vector((0, -3 * max(hi[0] - lo[0], 1000), 300))
    camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
    camera.data.clip_end = 100000  # the guide: clouds are kilometres across
    bpy.data.objects["Cube"].hide_render = True
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False  # the guide: Debian's Blender has no OpenImageDenoise
    scene.render.resolution_x, scene.render.resolution_y = 32, 24
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.render.filepath = os.path.join(work, "render.png")
    bpy.ops.render.render(write_still=True)
    alpha = list(bpy.data.images.load(scene.render.filepath).pixels)[3::4]
    covered = sum(a > 0.05 for a in alpha)
    check(covered > len(alpha) // 20, "the cloud covers %d of %d pixels" % (covered, len(alpha)))


def main():
    args = arguments()
    folder, cloud_frame = run_graph(args)
    volume, numbers = check_vdb_sequence(folder, cloud_frame)
    check_ply(os.path.join(folder, "particles.0000.ply"))  # WriteParticles: vapour
    frame = numbers[-1]
    points = check_ply(os.path.join(folder, "cloud.%04d.ply" % frame))  # the cloud's particles
    # Both in metres, z up: the volume of a frame encloses that frame's particles.
    vlo, vhi = bounds(evaluated(volume, frame))
    plo, phi = bounds(points)
    check(all(v <= p for v, p in zip(vlo, plo)) and all(v >= p for v, p in zip(vhi, phi)),
          "volume %s..%s does not enclose its particles %s..%s" % (vlo, vhi, plo, phi))
    check(all(p - v < 200 for v, p in zip(vlo, plo)), "volume far larger than its particles")
    check_render(volume, frame, args.work)
    print("check_outputs: Blender %s reads the VDB sequence %d..%d and the PLY files as the user "
          "guide says" % (bpy.app.version_string, numbers[0], numbers[-1]))


main()
